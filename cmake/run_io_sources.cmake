# The run readers (canonical and OpenACC CSV, plausibility and gap checks, the ACC's engagement
# reports, the input account):
# built into acc_run_io and, with clang's libFuzzer and sanitizers, into the run fuzzer
# (scripts/test_hooks/fuzz_run_csv.sh configures test/fuzz/CMakeLists.txt, which includes this file).
set(ACC_RUN_IO_SOURCES
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
  src/io/acc_engagement.cpp
  src/io/gap_kinematics.cpp
  src/io/gap_sawtooth.cpp
  src/io/input_account.cpp
  src/io/installed_beside.cpp
  src/io/output_files.cpp
  src/io/run_program.cpp
  src/io/repeated_recording.cpp)
