#!/usr/bin/env bash
# Fuzzes the run readers (test/fuzz/fuzz_run_csv.cpp: canonical and OpenACC CSV, every pair) with
# libFuzzer, AddressSanitizer and UndefinedBehaviorSanitizer for FUZZ_RUN_CSV_SECONDS (default
# 45), seeded by the run files the unit tests read (test/data/runs, test/data/openacc; inputs cut
# at 16 KiB, which holds a few hundred rows); RESULTS_DIR/fuzz_run_csv.xml says how it went.
# Usage: fuzz_run_csv.sh WORKSPACE RESULTS_DIR   (run by scripts/run_tests.sh)
set -uo pipefail
source "$(dirname "$0")/lib/libfuzzer.sh"
repo=$(cd "$(dirname "$0")/../.." && pwd)
run_libfuzzer_hook fuzz_run_csv "$1" "$2" "${FUZZ_RUN_CSV_SECONDS:-45}" "-max_len=16384" \
  "$repo/test/data/runs" "$repo/test/data/openacc"
