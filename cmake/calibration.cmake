# Calibration (paper Section IV): run I/O, the fast exact objective, multistart NLopt solves, the
# sliding window of the identifier; the calibrate tool, the identifier node, tests, benchmark.
find_package(nlohmann_json 3 REQUIRED)

# Run files (canonical and OpenACC CSV): used by every tool that takes runs.
add_library(acc_run_io src/io/run_csv.cpp src/io/run_plausibility.cpp)
target_include_directories(acc_run_io PUBLIC include)
target_link_libraries(acc_run_io PUBLIC acc_model)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_run_csv test/unit/gtest_main.cpp test/unit/test_run_csv.cpp)
  target_compile_definitions(test_run_csv PRIVATE ACC_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/test/data/runs")
  target_link_libraries(test_run_csv acc_run_io)
endif()

# The calibration core (ROS-free): objective with exact gradient, multistart NLopt, fit statistics,
# identifiability, the identifier's sliding window, synthetic runs for tests and benchmarks.
add_library(acc_calibration
  src/calibration/calibration_objective.cpp
  src/calibration/multistart_calibrator.cpp
  src/calibration/fit_statistics.cpp
  src/calibration/identification.cpp
  src/calibration/synthetic_runs.cpp
  src/calibration/sliding_window.cpp
  src/calibration/grid_search.cpp
  src/calibration/calibration_report.cpp)
target_include_directories(acc_calibration PUBLIC include ${EIGEN3_INCLUDE_DIR})
target_link_libraries(acc_calibration PUBLIC acc_model ${ACC_NLOPT_TARGET} nlohmann_json::nlohmann_json)
install(TARGETS acc_run_io acc_calibration
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})

# ROS side: runs from bags of RelativeState (rosbag API).
add_library(acc_calibration_ros src/ros/run_bag_reader.cpp)
target_include_directories(acc_calibration_ros PUBLIC include ${catkin_INCLUDE_DIRS})
target_link_libraries(acc_calibration_ros acc_calibration acc_run_io ${catkin_LIBRARIES})
add_dependencies(acc_calibration_ros ${PROJECT_NAME}_generate_messages_cpp)

# rosrun acc_identification calibrate [options] RUN...
add_executable(calibrate src/tools/calibrate_main.cpp)
target_link_libraries(calibrate acc_calibration_ros acc_run_io acc_cli)
install(TARGETS acc_calibration_ros calibrate
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_calibration
    test/unit/gtest_main.cpp
    test/unit/test_calibration_objective.cpp
    test/unit/test_calibration_multistart.cpp
    test/unit/test_identifier_window.cpp
    test/unit/test_calibration_report.cpp)
  target_compile_definitions(test_calibration PRIVATE ACC_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/test/data/runs")
  target_link_libraries(test_calibration acc_calibration acc_run_io)
endif()

# Benchmarks: a plain executable (not a test), run by `make bench`.
find_package(benchmark QUIET)
if(benchmark_FOUND)
  add_executable(bench_calibration bench/bench_calibration.cpp)
  target_link_libraries(bench_calibration acc_calibration benchmark::benchmark)
endif()

# identifier_node: the sliding-window identifier (ROS wrapper and its ten-line main).
add_library(acc_identifier_ros src/ros/identifier_ros.cpp)
target_include_directories(acc_identifier_ros PUBLIC include ${catkin_INCLUDE_DIRS})
target_link_libraries(acc_identifier_ros acc_calibration ${catkin_LIBRARIES})
add_dependencies(acc_identifier_ros ${PROJECT_NAME}_generate_messages_cpp)
add_executable(identifier_node src/nodes/identifier_node.cpp)
target_link_libraries(identifier_node acc_identifier_ros)
install(TARGETS acc_identifier_ros identifier_node
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(FILES launch/identifier.launch DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/launch)
install(FILES config/identifier.yaml DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/config)

if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  # relative_state in, acc_parameters out, on simulated time.
  add_rostest_gtest(test_identifier_rostest test/rostest/identifier.test test/rostest/identifier_check.cpp)
  target_include_directories(test_identifier_rostest PRIVATE include ${catkin_INCLUDE_DIRS})
  target_link_libraries(test_identifier_rostest acc_calibration ${catkin_LIBRARIES})
  add_dependencies(test_identifier_rostest ${PROJECT_NAME}_generate_messages_cpp identifier_node)

  # The ROS-side pieces that need no master: bags in, messages out.
  catkin_add_gtest(test_calibration_ros
    test/unit/gtest_main.cpp
    test/unit/test_calibration_bag.cpp
    test/unit/test_identifier_message.cpp)
  target_link_libraries(test_calibration_ros acc_calibration_ros acc_identifier_ros)
endif()
