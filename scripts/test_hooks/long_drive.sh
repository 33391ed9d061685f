#!/usr/bin/env bash
# A three-hour drive through the whole chain at 50x (test/field/long_drive_check.py, about 4 min):
# every node's memory stays level (the identifier's drive so far within ~drive_max_samples) and the
# latency does not grow. Writes RESULTS_DIR/long_drive.xml and the figure and numbers beside it.
# Usage: long_drive.sh WORKSPACE RESULTS_DIR   (run by scripts/run_tests.sh, devel space sourced)
set -uo pipefail
ws=$1
results=$2
here=$(cd "$(dirname "$0")" && pwd)
source "$here/lib/junit.sh"
out=$results/long_drive
mkdir -p "$out"
start=$(date +%s)
if /usr/bin/python3 "$here/../../test/field/long_drive_check.py" "$ws" "$out" --rate 50 > "$out/check.log" 2>&1; then
  write_junit "$results/long_drive.xml" long_drive three_hours_at_50x $(( $(date +%s) - start ))
  echo "long_drive: passed ($(tr -d '\n ' < "$out/long_drive.json" | grep -o '"/identifier":{[^}]*}'))"
else
  write_junit "$results/long_drive.xml" long_drive three_hours_at_50x $(( $(date +%s) - start )) \
    "a node's memory or latency grew over the three-hour drive (or the check failed)" "$out/check.log"
  echo "long_drive: FAILED"; tail -n 30 "$out/check.log"
  exit 1
fi
