# The relative state (pairing by GNSS epoch, the gap, the jump and consistency checks): built into
# acc_relative_state and, with clang's libFuzzer and sanitizers, into the relative-state fuzzer
# (scripts/test_hooks/fuzz_relative_state.sh configures test/fuzz/CMakeLists.txt, which includes this file).
set(ACC_RELATIVE_STATE_SOURCES
  src/relative_state/epoch_pairing.cpp
  src/relative_state/vehicle_geometry.cpp
  src/relative_state/gap_doppler_consistency.cpp
  src/relative_state/gap_step_check.cpp
  src/relative_state/relative_state_estimator.cpp)
