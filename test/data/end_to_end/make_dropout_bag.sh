#!/usr/bin/env bash
# Remakes leader_dropout_5s.bag: the first 180 s of bags/synthetic_max_F.bag with the leader's
# sentences from 90 s to 95 s after the start removed (a 5 s dropout of the lead car's receiver;
# the follower's receiver goes on). Needs python3-rosbag (rosbag filter).
set -eo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source_bag=$here/../../../bags/synthetic_max_F.bag
start=1778580000   # the synthetic drive's start (bags/synthetic_max_F_parameters.json)
export PATH=/usr/bin:$PATH
rosbag filter "$source_bag" "$here/leader_dropout_5s.bag" \
  "t.to_sec() < $start + 180 and not (topic == '/leader/nmea_sentence' and $start + 90 <= t.to_sec() < $start + 95)"
rosbag compress --lz4 "$here/leader_dropout_5s.bag" > /dev/null
rm -f "$here/leader_dropout_5s.orig.bag"
