#!/usr/bin/env bash
# The package as another catkin package sees it: installs the workspace (catkin_make install),
# then builds test/catkin_consumer, a second package that finds the INSTALLED acc_identification
# (only the install space on CMAKE_PREFIX_PATH, never the devel space or the sources), includes
# its headers and messages and links its libraries, and runs it. Writes RESULTS_DIR/
# installed_package.xml (JUnit, one test case).
# Usage: installed_package.sh WORKSPACE RESULTS_DIR   (run by scripts/run_tests.sh)
set -uo pipefail
ws=$1
results=$2
repo=$(cd "$(dirname "$0")/../.." && pwd)
work=$ws/build/installed_package
log=$work/installed_package.log
xml=$results/installed_package.xml
rm -rf "$work"
mkdir -p "$work/consumer_ws/src" "$results"
start=$(date +%s)

source "$(dirname "$0")/lib/junit.sh"
fail() {
  write_junit "$xml" installed_package second_catkin_package_links_the_installed_libraries \
    $(( $(date +%s) - start )) "$1" "$log"
  echo "installed_package: FAILED: $1 (log: $log)"; exit 1; }

(cd "$ws" && catkin_make -j"${JOBS:-2}" install) > "$log" 2>&1 || fail "catkin_make install failed"
cp -r "$repo/test/catkin_consumer" "$work/consumer_ws/src/acc_identification_consumer"
# A clean environment: Debian's own ROS in /usr, and our package only from the install space.
env -i HOME="$HOME" PATH=/usr/bin:/bin:/usr/sbin:/sbin LANG=C.UTF-8 bash -c '
  set -e
  source "$1/install/local_setup.bash"  # this workspace alone, not the devel space it was built from
  case ":$CMAKE_PREFIX_PATH:" in *"/devel"*) echo "devel space on CMAKE_PREFIX_PATH" >&2; exit 1;; esac
  cd "$2" && catkin_make -j1 > catkin_make.log 2>&1 || { tail -n 40 catkin_make.log; exit 1; }
  ./devel/lib/acc_identification_consumer/acc_identification_consumer
' consumer "$ws" "$work/consumer_ws" >> "$log" 2>&1 || fail "the consumer package did not build or run"
grep -q '^consumer: lambda2 70.67, gga parsed' "$log" || fail "the consumer printed unexpected values"
write_junit "$xml" installed_package second_catkin_package_links_the_installed_libraries $(( $(date +%s) - start ))
echo "installed_package: $(grep '^consumer:' "$log")"
