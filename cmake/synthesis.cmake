# Synthetic drives (issue 5): a lead profile of the paper, a follower by the ACC model (with the
# diagnosis's unmodelled effects on request), both cars on a curved road, each receiver with its
# GNSS errors, written as NMEA logs, truth CSV, parameters JSON and bags. The ROS-free library
# acc_synthesis, the synthesize tool, and their tests; bags are written by gnss.cmake's
# acc_sentence_bag. Builds on the gnss and relative_state components (NMEA writer and reader, geodesy) and reproduction (lead profiles A-I);
# the follower with its effects is the model core's simulator.
if(NOT (TARGET acc_conversion AND TARGET acc_reproduction))
  message(WARNING "synthesis needs the gnss, relative_state and reproduction components in "
                  "ACC_COMPONENTS: not built")
  return()
endif()
acc_add_library(acc_synthesis
  SOURCES
    src/synthesis/gnss_error_model.cpp
    src/synthesis/road_centreline.cpp
    src/synthesis/drive_truth.cpp
    src/synthesis/synthesis.cpp
    src/synthesis/synthesis_output.cpp
  LINK acc_conversion acc_relative_state acc_reproduction ${GeographicLib_LIBRARIES})
target_link_libraries(acc_synthesis PRIVATE nlohmann_json::nlohmann_json)

acc_add_tool(synthesize LINK acc_synthesis acc_sentence_bag)
install(PROGRAMS scripts/make_bags.sh DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_synthesis
    test/unit/gtest_main.cpp
    test/unit/test_synthesis.cpp
    test/unit/test_synthesis_noise.cpp
    test/unit/test_synthesis_bag.cpp)
  target_link_libraries(test_synthesis acc_synthesis acc_sentence_bag)
  target_compile_definitions(test_synthesis PRIVATE ACC_SYNTHESIS_BAGS_DIR="${PROJECT_SOURCE_DIR}/bags"
    ACC_OPENACC_DATA_DIR="${ACC_DATA_CASALE_DIR}" ACC_ZALAZONE_DATA_DIR="${ACC_DATA_ZALAZONE_TOYOTA_RAV4_S_DIR}")
endif()
