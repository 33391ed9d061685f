# Run files: canonical and OpenACC CSV (csv_fields: one line's fields, quotes and a byte-order
# mark as spreadsheet exports write them) read into runs, with the plausibility checks every reader
# of runs (CSV or bag) shares (run_plausibility per sample, gap_kinematics per run: the gap against
# the integrated speeds, over seconds and, gap_sawtooth, sample by sample). Used by every tool that takes runs. openacc_file.cpp is the one
# reader of OpenACC files (every layout); the runs and the NMEA conversion are views on it. Its
# pieces: openacc_text (fields, cells, column names), openacc_angle_unit (radians or degrees),
# openacc_pairs (which leader-follower pairs a file holds, and the one chosen). mixed_setting_listing
# reads the database's table of the cars at the other setting in its mixed-setting runs.
acc_add_library(acc_run_io
  SOURCES
    src/io/csv_fields.cpp
    src/io/openacc_file.cpp
    src/io/openacc_text.cpp
    src/io/openacc_angle_unit.cpp
    src/io/openacc_pairs.cpp
    src/io/distance_setting.cpp
    src/io/mixed_setting_listing.cpp
    src/io/problem_lines.cpp
    src/io/run_csv.cpp
    src/io/run_plausibility.cpp
    src/io/gap_kinematics.cpp
    src/io/gap_sawtooth.cpp
    src/io/input_account.cpp
    src/io/installed_beside.cpp
    src/io/output_files.cpp
  LINK acc_model nlohmann_json::nlohmann_json)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_run_csv test/unit/gtest_main.cpp test/unit/test_run_csv.cpp test/unit/test_openacc_file.cpp
    test/unit/test_gap_kinematics.cpp test/unit/test_gap_sawtooth.cpp
    test/unit/test_output_files.cpp test/unit/test_input_account.cpp)
  target_compile_definitions(test_run_csv PRIVATE ACC_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/test/data/runs")
  target_link_libraries(test_run_csv acc_run_io)
endif()
