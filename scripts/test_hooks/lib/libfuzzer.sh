# Sourced by the fuzzing hooks: run_libfuzzer_hook NAME WORKSPACE RESULTS_DIR SECONDS FLAGS SEED_DIR...
# builds the libFuzzer target NAME of test/fuzz/CMakeLists.txt with clang (AddressSanitizer and
# UndefinedBehaviorSanitizer; one build folder for every target), fuzzes it for SECONDS from the
# seed folders (only read; new inputs go to a work corpus) with the extra libFuzzer FLAGS, and
# writes RESULTS_DIR/NAME.xml (JUnit, one test case; a failure with the crash report on any crash,
# sanitizer finding, invariant violation or build error). Returns non-zero on a failure.
# The seed is fixed (FUZZ_SEED, default 1): make test on a user's machine tries the inputs CI tried
# (as many as its speed allows in SECONDS), so a latent bug fails CI first, not a user's build.
# FUZZ_SEED=0 draws a seed (libFuzzer's own rule), to explore beyond them.
source "$(dirname "${BASH_SOURCE[0]}")/junit.sh"

run_libfuzzer_hook() {
  local name=$1 ws=$2 results=$3 seconds=$4 flags=$5
  shift 5
  local repo build work log xml start status elapsed runs summary
  repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
  build=$ws/build/fuzz_targets
  work=$ws/build/$name
  log=$work/fuzz.log
  xml=$results/$name.xml
  mkdir -p "$work/corpus" "$results"
  : > "$log"
  start=$(date +%s)
  if ! { cmake -S "$repo/test/fuzz" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None \
           && cmake --build "$build" --target "$name" -j "${JOBS:-2}" && cp "$build/$name" "$work/$name"; } >> "$log" 2>&1; then
    write_junit "$xml" "$name" "$name" 0 "$name did not build" "$log"
    echo "$name: build failed (see $log)"
    return 1
  fi
  # shellcheck disable=SC2086  # FLAGS are words for libFuzzer
  "$work/$name" -seed="${FUZZ_SEED:-1}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 $flags \
    -artifact_prefix="$work/" "$work/corpus" "$@" >> "$log" 2>&1
  status=$?
  elapsed=$(( $(date +%s) - start ))
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -n 1)
  if [ "$status" -ne 0 ]; then
    summary=$(grep -m1 -E 'ERROR: |runtime error|invariant violated|deadly signal|uncaught exception' "$log" \
              || echo "exit status $status")
    write_junit "$xml" "$name" "$name" "$elapsed" "$name found a crash: $summary (artifacts in $work)" "$log"
    echo "$name: CRASH ($summary); report in $log"
    return 1
  fi
  write_junit "$xml" "$name" "$name" "$elapsed"
  echo "$name: ${runs:-?} inputs in ${elapsed} s, no crash"
}
