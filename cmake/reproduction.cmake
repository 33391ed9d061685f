# Reproduction of the paper's analyses and figures (issue 7): the numbers behind each figure as a
# ROS-free library, the lead profiles A-I of Section III, and the `platoon` command-line tool.
find_package(nlohmann_json 3 REQUIRED)

add_library(acc_reproduction
  src/reproduction/lead_profiles.cpp
  src/reproduction/lambda2_map.cpp
  src/reproduction/frequency_response.cpp
  src/reproduction/lead_inputs.cpp
  src/reproduction/platoon_metrics.cpp
  src/reproduction/platoon_responses.cpp
  src/reproduction/run_comparison.cpp
  src/reproduction/parameter_file.cpp)
target_include_directories(acc_reproduction PUBLIC include ${EIGEN3_INCLUDE_DIR})
target_link_libraries(acc_reproduction PUBLIC acc_model PRIVATE nlohmann_json::nlohmann_json)

# Runs for Figs. 3-5 are read with the package's run reader (io/run_csv.h), which the calibration
# component builds; when that component is not selected, build the same library here.
if(NOT TARGET acc_run_io)
  add_library(acc_run_io src/io/run_csv.cpp)
  target_include_directories(acc_run_io PUBLIC include)
  target_link_libraries(acc_run_io PUBLIC acc_model)
endif()

add_executable(platoon src/tools/platoon_main.cpp)
target_link_libraries(platoon acc_reproduction acc_run_io acc_cli nlohmann_json::nlohmann_json)
install(TARGETS acc_reproduction platoon
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(PROGRAMS scripts/plot_figures.py scripts/reproduce_figures.sh
  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_reproduction
    test/unit/gtest_main.cpp
    test/unit/test_lead_profiles.cpp
    test/unit/test_reproduction_lambda2_map.cpp
    test/unit/test_reproduction_frequency_response.cpp
    test/unit/test_reproduction_platoon.cpp
    test/unit/test_reproduction_runs.cpp)
  target_link_libraries(test_reproduction acc_reproduction)
endif()
