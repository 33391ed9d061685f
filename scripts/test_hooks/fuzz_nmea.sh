#!/usr/bin/env bash
# Fuzzes the NMEA parser and line/epoch assembly (test/fuzz/fuzz_nmea.cpp) with libFuzzer,
# AddressSanitizer and UndefinedBehaviorSanitizer for FUZZ_NMEA_SECONDS (default 60), from the
# seed corpus test/fuzz/corpus_nmea; RESULTS_DIR/fuzz_nmea.xml says how it went (lib/libfuzzer.sh).
# Usage: fuzz_nmea.sh WORKSPACE RESULTS_DIR   (run by scripts/run_tests.sh)
set -uo pipefail
source "$(dirname "$0")/lib/libfuzzer.sh"
repo=$(cd "$(dirname "$0")/../.." && pwd)
run_libfuzzer_hook fuzz_nmea "$1" "$2" "${FUZZ_NMEA_SECONDS:-60}" "" "$repo/test/fuzz/corpus_nmea"
