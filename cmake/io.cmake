# Run files: canonical and OpenACC CSV (csv_fields: one line's fields, quotes and a byte-order
# mark as spreadsheet exports write them) read into runs, with the plausibility checks every reader
# of runs (CSV or bag) shares (run_plausibility per sample, gap_kinematics per run: the gap against
# the integrated speeds, over seconds and, gap_sawtooth, sample by sample). Used by every tool that takes runs. openacc_file.cpp is the one
# reader of OpenACC files (every layout); the runs and the NMEA conversion are views on it. Its
# pieces: openacc_text (fields, cells, column names), openacc_angle_unit (radians or degrees),
# openacc_pairs (which leader-follower pairs a file holds, and the one chosen). mixed_setting_listing
# reads the database's table of the cars at the other setting in its mixed-setting runs;
# repeated_recording tells the same recording given twice (a copy, an excerpt) by its speeds.
# The sources are one list: the run fuzzer (scripts/test_hooks/fuzz_run_csv.sh) builds the same files
# with clang's libFuzzer from cmake/run_io_sources.cmake.
include(${CMAKE_CURRENT_LIST_DIR}/run_io_sources.cmake)
acc_add_library(acc_run_io SOURCES ${ACC_RUN_IO_SOURCES} LINK acc_model nlohmann_json::nlohmann_json)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_run_csv test/unit/gtest_main.cpp test/unit/test_run_csv.cpp test/unit/test_openacc_file.cpp
    test/unit/test_gap_kinematics.cpp test/unit/test_gap_sawtooth.cpp
    test/unit/test_output_files.cpp test/unit/test_input_account.cpp test/unit/test_acc_engagement.cpp
    test/unit/test_repeated_recording.cpp)
  target_compile_definitions(test_run_csv PRIVATE ACC_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/test/data/runs")
  target_link_libraries(test_run_csv acc_run_io)
endif()
