#!/usr/bin/env bash
# Builds and runs every gtest and rostest of the package, then fails if any test failed or errored.
# Usage: run_tests.sh WORKSPACE   (with the workspace's devel/setup.bash sourced)
set -eo pipefail
here=$(cd "$(dirname "$0")" && pwd)
ws=$1
results=$ws/build/test_results
log=$ws/run_tests.log
rm -rf "$results"
cd "$ws"
catkin_make -j"${JOBS:-2}" run_tests > "$log" 2>&1 || { tail -n 80 "$log"; echo "run_tests failed to build or run"; exit 1; }
# Extra suites outside catkin (fuzzers, ...): each hook gets the workspace and the results folder
# and writes its own JUnit XML there, so that the summary below counts it.
# A hook writes RESULTS/<hook name>.xml; one that fails without writing it (it crashed) gets a
# failing file here, so that a crash is never a silent pass.
source "$here/test_hooks/lib/junit.sh"
for hook in "$here"/test_hooks/*.sh; do
  [ -e "$hook" ] || continue
  name=$(basename "$hook" .sh)
  echo "== $name"
  rm -f "$results/$name.xml"
  hook_start=$(date +%s)
  if ! bash "$hook" "$ws" "$results" > "$ws/hook_$name.log" 2>&1; then
    echo "hook $name failed (its JUnit file says why)"
  fi
  cat "$ws/hook_$name.log"
  if [ ! -s "$results/$name.xml" ]; then
    write_junit "$results/$name.xml" "$name" hook_wrote_no_result $(( $(date +%s) - hook_start )) \
      "the hook $name ended without writing its results" "$ws/hook_$name.log"
    echo "hook $name wrote no results: counted as a failure"
  fi
done
# The per-binary lines, for a reader of the CI log.
grep -E '^\[  (FAILED|PASSED)|^\[==========\] [0-9]+ tests? from .* ran|^\[ROSTEST\]|^SUMMARY|^ \* RESULT' "$log" || true
# catkin_test_results also catches a test binary that crashed before writing its results.
set +e
catkin_test_results "$results" | grep -E '^Summary|^acc_identification/.*(error|failure)' | grep -vE ' 0 errors, 0 failures' 
catkin_status=${PIPESTATUS[0]}
/usr/bin/python3 "$here/summarize_test_results.py" "$results"
summary_status=$?
set -e
[ "$catkin_status" -eq 0 ] && [ "$summary_status" -eq 0 ]
