# Calibration (paper Section IV): run I/O, the fast exact objective, multistart NLopt solves, the
# sliding window of the identifier; the calibrate tool, the identifier node, tests, benchmark.
find_package(nlohmann_json 3 REQUIRED)

# Run files (canonical and OpenACC CSV): used by every tool that takes runs.
add_library(acc_run_io src/io/run_csv.cpp)
target_include_directories(acc_run_io PUBLIC include)
target_link_libraries(acc_run_io PUBLIC acc_model)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_run_csv test/unit/gtest_main.cpp test/unit/test_run_csv.cpp)
  target_compile_definitions(test_run_csv PRIVATE ACC_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/test/data/runs")
  target_link_libraries(test_run_csv acc_run_io)
endif()
