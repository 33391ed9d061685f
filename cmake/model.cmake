# The model core: the ACC law, simulation of one follower and of a platoon, string stability.
add_library(acc_model
  src/model/acc_model.cpp
  src/model/car_following_run.cpp
  src/model/follower_simulation.cpp
  src/model/platoon_simulation.cpp
  src/model/string_stability.cpp
  src/model/paper_settings.cpp)
target_include_directories(acc_model PUBLIC include ${EIGEN3_INCLUDE_DIR})
target_link_libraries(acc_model PUBLIC m)

# Shared by every command-line tool: option parsing with clear messages.
add_library(acc_cli src/tools/command_line.cpp)
target_include_directories(acc_cli PUBLIC include)

add_executable(stability_report src/tools/stability_report_main.cpp)
target_link_libraries(stability_report acc_model acc_cli)
install(TARGETS acc_model stability_report
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_model
    test/unit/gtest_main.cpp
    test/unit/test_acc_model.cpp
    test/unit/test_string_stability.cpp
    test/unit/test_follower_simulation.cpp
    test/unit/test_platoon_simulation.cpp)
  target_link_libraries(test_model acc_model)
endif()
