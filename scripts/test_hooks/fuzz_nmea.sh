#!/usr/bin/env bash
# Fuzzes the NMEA parser and line/epoch assembly (test/fuzz/fuzz_nmea.cpp) with libFuzzer,
# AddressSanitizer and UndefinedBehaviorSanitizer for FUZZ_NMEA_SECONDS (default 60) and writes
# RESULTS_DIR/fuzz_nmea.xml (JUnit, one test case; a failure with the crash report on any crash,
# sanitizer finding, invariant violation or build error).
# Usage: fuzz_nmea.sh WORKSPACE RESULTS_DIR   (run by scripts/run_tests.sh)
set -uo pipefail
ws=$1
results=$2
repo=$(cd "$(dirname "$0")/../.." && pwd)
seconds=${FUZZ_NMEA_SECONDS:-60}
work=$ws/build/fuzz_nmea
mkdir -p "$work/corpus" "$results"
log=$work/fuzz.log
xml=$results/fuzz_nmea.xml

source "$(dirname "$0")/lib/junit.sh"

start=$(date +%s)
# The parser's own source list (cmake/gnss_parser_sources.cmake), built by clang with libFuzzer.
if ! { cmake -S "$repo/test/fuzz" -B "$work/build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None \
         && cmake --build "$work/build" -j "${JOBS:-2}" && cp "$work/build/fuzz_nmea" "$work/fuzz_nmea"; } > "$log" 2>&1; then
  write_junit "$xml" fuzz_nmea fuzz_nmea 0 "fuzz_nmea did not build" "$log"
  echo "fuzz_nmea: build failed (see $log)"
  exit 1
fi
# New inputs go to the work corpus; the seed corpus in the repository is only read.
"$work/fuzz_nmea" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$work/" "$work/corpus" "$repo/test/fuzz/corpus_nmea" >> "$log" 2>&1
status=$?
elapsed=$(( $(date +%s) - start ))
runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -n 1)
if [ "$status" -ne 0 ]; then
  summary=$(grep -m1 -E 'ERROR: |runtime error|invariant violated|deadly signal' "$log" || echo "exit status $status")
  write_junit "$xml" fuzz_nmea fuzz_nmea "$elapsed" "fuzz_nmea found a crash: $summary (artifacts in $work)" "$log"
  echo "fuzz_nmea: CRASH ($summary); report in $log"
  exit 1
fi
write_junit "$xml" fuzz_nmea fuzz_nmea "$elapsed"
echo "fuzz_nmea: ${runs:-?} inputs in ${elapsed} s, no crash"
