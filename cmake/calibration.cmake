# Calibration (paper Section IV): the fast exact objective, multistart NLopt solves, fit
# statistics, identifiability and the identifier's sliding window (ROS-free); runs from bags; the
# calibrate tool, the identifier node, tests and a benchmark.
acc_add_library(acc_calibration
  SOURCES
    src/calibration/calibration_objective.cpp
    src/calibration/multistart_calibrator.cpp
    src/calibration/fit_statistics.cpp
    src/calibration/identification.cpp
    src/calibration/sliding_window.cpp
    src/calibration/drive_record.cpp
    src/calibration/grid_search.cpp
    src/calibration/calibration_report.cpp
    src/calibration/margin_constrained_fit.cpp
    src/calibration/quantity_identifiability.cpp
    src/calibration/side_fits.cpp
    src/calibration/betting_e_process.cpp
    src/calibration/sequential_verdict.cpp
    src/calibration/sequential_verdict_report.cpp
    src/calibration/held_out_side_comparison.cpp
    src/calibration/string_stability_verdict.cpp
    src/calibration/string_stability_verdict_json.cpp
    src/calibration/string_stability_verdict_text.cpp
    src/calibration/online_identifier.cpp
    src/calibration/model_dip_check.cpp
    src/calibration/model_adequacy.cpp
    src/calibration/calibrate_runs.cpp
    src/calibration/fit_traces.cpp
    src/calibration/euler_step_bias.cpp
    src/calibration/refit_bootstrap.cpp
  LINK acc_evidence acc_run_io acc_model ${ACC_NLOPT_TARGET} nlohmann_json::nlohmann_json)

# Car-following runs made from known parameters (synthesis/synthetic_runs.h): the seeded truths
# the calibration's tests, benchmarks and verdict_study recover. Beside the calibration, whose
# margin projection places a truth at a chosen stability margin.
acc_add_library(acc_synthetic_runs SOURCES src/synthesis/synthetic_runs.cpp src/synthesis/verdict_study.cpp
  LINK acc_calibration)

# ROS side: runs from bags of RelativeState (rosbag API), with the CSV reader's checks.
acc_add_ros_library(acc_calibration_ros SOURCES src/ros/run_bag_reader.cpp src/ros/run_input_options.cpp
  LINK acc_calibration acc_run_io CLI11::CLI11)

# rosrun acc_identification calibrate [options] RUN...
acc_add_tool(calibrate LINK acc_calibration_ros acc_run_io acc_sumo)
# Its second opinion where the model does not describe the data is the diagnosis (cmake/diagnosis.cmake).
if(TARGET acc_diagnosis OR "diagnosis" IN_LIST ACC_COMPONENTS)
  target_link_libraries(calibrate acc_diagnosis)
  target_compile_definitions(calibrate PRIVATE ACC_WITH_DIAGNOSIS=1)
endif()
# calibrate --report finds its figure script next to itself, as diagnose and campaign do.
configure_file(scripts/plot_calibration.py
  ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION}/plot_calibration.py COPYONLY)
configure_file(scripts/report_headline.py
  ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION}/report_headline.py COPYONLY)
install(PROGRAMS scripts/plot_calibration.py scripts/report_headline.py
  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

# rosrun acc_identification verdict_study --drives N: size and power of the sequential verdict.
acc_add_tool(verdict_study LINK acc_calibration acc_synthetic_runs)

# identifier_node: the sliding-window identifier (ROS wrapper and its ten-line main).
acc_add_ros_library(acc_identifier_ros SOURCES src/ros/identifier_ros.cpp src/ros/stability_look_schedule.cpp LINK acc_calibration acc_run_io
  acc_ros_parameters)
acc_add_node(identifier_node WRAPPER acc_identifier_ros)

acc_add_benchmark(bench_calibration LINK acc_calibration acc_synthetic_runs)
acc_add_benchmark(bench_string_stability_verdict LINK acc_calibration acc_synthetic_runs)
acc_add_benchmark(bench_online_identifier LINK acc_calibration acc_synthetic_runs)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_calibration
    test/unit/gtest_main.cpp
    test/unit/test_calibration_objective.cpp
    test/unit/test_calibration_multistart.cpp
    test/unit/test_identifier_window.cpp
    test/unit/test_drive_record.cpp
    test/unit/test_calibration_report.cpp
    test/unit/test_synthetic_runs.cpp
    test/unit/test_model_adequacy.cpp
    test/unit/test_model_dip_check.cpp
    test/unit/test_euler_step_bias.cpp
    test/unit/test_standard_error_coverage.cpp
    test/unit/test_refit_bootstrap.cpp)
  target_compile_definitions(test_calibration PRIVATE ACC_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/test/data/runs")
  target_link_libraries(test_calibration acc_calibration acc_run_io acc_synthetic_runs)

  # The string-stability test (string_stability_verdict.h) on seeded synthetic drives: size, power, interval.
  catkin_add_gtest(test_string_stability_verdict test/unit/gtest_main.cpp test/unit/test_string_stability_verdict.cpp
    test/unit/test_held_out_side_comparison.cpp)
  target_link_libraries(test_string_stability_verdict acc_calibration)

  # The sequential verdict: betting under H0, synthetic truths decided and kept, node path = replay.
  catkin_add_gtest(test_sequential_verdict test/unit/gtest_main.cpp test/unit/test_sequential_verdict.cpp)
  target_link_libraries(test_sequential_verdict acc_calibration acc_synthetic_runs)

  # The live identifier's computation: the drive so far converges to the batch estimate and verdict.
  catkin_add_gtest(test_online_identifier test/unit/gtest_main.cpp test/unit/test_online_identifier.cpp)
  target_link_libraries(test_online_identifier acc_calibration acc_synthetic_runs)

  # The ROS-side pieces that need no master: bags in, messages out.
  catkin_add_gtest(test_calibration_ros
    test/unit/gtest_main.cpp
    test/unit/test_calibration_bag.cpp
    test/unit/test_identifier_message.cpp
    test/unit/test_identifier_health.cpp
    test/unit/test_stability_look_schedule.cpp
    test/unit/test_number_checks.cpp)
  target_link_libraries(test_calibration_ros acc_calibration_ros acc_identifier_ros acc_synthetic_runs)

  # relative_state in, acc_parameters out, on simulated time.
  add_rostest_gtest(test_identifier_rostest test/rostest/identifier.test test/rostest/identifier_check.cpp)
  target_include_directories(test_identifier_rostest PRIVATE include ${catkin_INCLUDE_DIRS})
  target_link_libraries(test_identifier_rostest acc_calibration acc_synthetic_runs ${catkin_LIBRARIES})
  add_dependencies(test_identifier_rostest ${PROJECT_NAME}_generate_messages_cpp identifier_node)

  # A 1 Hz stream: the Euler step checked live, and a ~max_gap_s below the step said to be one.
  add_rostest_gtest(test_identifier_coarse_rostest test/rostest/identifier_coarse.test
    test/rostest/identifier_coarse_check.cpp)
  target_include_directories(test_identifier_coarse_rostest PRIVATE include ${catkin_INCLUDE_DIRS})
  target_link_libraries(test_identifier_coarse_rostest acc_synthetic_runs ${catkin_LIBRARIES})
  add_dependencies(test_identifier_coarse_rostest ${PROJECT_NAME}_generate_messages_cpp identifier_node)

  # The node's wrapper in the test process with an injected solve: input faults, throwing solves.
  add_rostest_gtest(test_identifier_faults_rostest test/rostest/identifier_faults.test
    test/rostest/identifier_faults_check.cpp)
  target_link_libraries(test_identifier_faults_rostest acc_identifier_ros)
endif()
