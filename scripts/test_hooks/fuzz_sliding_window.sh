#!/usr/bin/env bash
# Fuzzes the identifier's sliding window (test/fuzz/fuzz_sliding_window.cpp: samples late, repeated,
# jumping back and ahead, not numbers, invalid or already counted, under window settings drawn from
# their ranges) with libFuzzer, AddressSanitizer and UndefinedBehaviorSanitizer for
# FUZZ_SLIDING_WINDOW_SECONDS (default 20), from an empty corpus (the inputs are choices, not
# text); RESULTS_DIR/fuzz_sliding_window.xml says how it went.
# Usage: fuzz_sliding_window.sh WORKSPACE RESULTS_DIR   (run by scripts/run_tests.sh)
set -uo pipefail
source "$(dirname "$0")/lib/libfuzzer.sh"
run_libfuzzer_hook fuzz_sliding_window "$1" "$2" "${FUZZ_SLIDING_WINDOW_SECONDS:-20}" "-max_len=8192"
