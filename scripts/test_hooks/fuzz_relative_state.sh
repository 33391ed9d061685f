#!/usr/bin/env bash
# Fuzzes the relative state (test/fuzz/fuzz_relative_state.cpp: two receivers' fixes paired by
# GNSS epoch, late, repeated, reset or not numbers at all, under settings drawn from their ranges)
# with libFuzzer, AddressSanitizer and UndefinedBehaviorSanitizer for FUZZ_RELATIVE_STATE_SECONDS
# (default 30), from an empty corpus (the inputs are choices, not text); RESULTS_DIR/fuzz_relative_state.xml
# says how it went.
# Usage: fuzz_relative_state.sh WORKSPACE RESULTS_DIR   (run by scripts/run_tests.sh)
set -uo pipefail
source "$(dirname "$0")/lib/libfuzzer.sh"
run_libfuzzer_hook fuzz_relative_state "$1" "$2" "${FUZZ_RELATIVE_STATE_SECONDS:-30}" "-max_len=8192"
