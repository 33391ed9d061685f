#!/usr/bin/env bash
# Two computers over a lossy radio link, in two network namespaces this test makes and removes
# (test/field/lossy_link_test.py): the leader's NMEA over UDP and ROS multi-machine, each over the
# same impaired link (scripts/tun_link_emulator.py). Needs root (ip netns, TUN devices); writes
# RESULTS_DIR/lossy_link.xml and the measured table RESULTS_DIR/lossy_link.txt.
# Usage: lossy_link.sh WORKSPACE RESULTS_DIR   (run by scripts/run_tests.sh)
set -uo pipefail
ws=$1
results=$2
here=$(cd "$(dirname "$0")" && pwd)
source "$here/lib/junit.sh"
if [ "$(id -u)" -ne 0 ]; then
  write_junit "$results/lossy_link.xml" lossy_link needs_root 0 "the two-computer test makes network namespaces: run make test as root"
  echo "lossy_link: FAILED: not root"; exit 1
fi
/usr/bin/python3 "$here/../../test/field/lossy_link_test.py" "$ws" "$results"
