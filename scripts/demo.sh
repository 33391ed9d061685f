#!/usr/bin/env bash
# The main job on the bundled default data. Run through `make demo`, with the workspace sourced.
#   1. the string stability of the paper's calibrated settings (Table II);
#   2. the bundled real-data bag (JRC OpenACC, Casale) replayed through replay.launch at a high rate:
#      the drivers decode the raw sentences, relative_state pairs the fixes, the identifier
#      recalibrates; one line per acc_parameters update;
#   3. a batch `calibrate` of the very relative_state samples of the identifier's last window, side
#      by side with the online result.
# Environment: DEMO_BAG, DEMO_RATE (default 20), DEMO_WINDOW_S (default 300: the whole run),
# DEMO_PERIOD_S (default 10), DEMO_PORT (ROS master port, default 11430).
set -eo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
package=$(cd "$here/.." && pwd)
bag=${DEMO_BAG:-$package/bags/casale_part3_sentences.bag}
rate=${DEMO_RATE:-20}
window_s=${DEMO_WINDOW_S:-300}
period_s=${DEMO_PERIOD_S:-10}
port=${DEMO_PORT:-11430}

echo "== String stability of the paper's calibrated ACC settings (Gunter et al., Table II) =="
rosrun acc_identification stability_report

echo
echo "== Online identification: $(basename "$bag") replayed at ${rate}x through replay.launch =="
echo "   (window ${window_s} s, an update every ${period_s} s of bag time)"
echo "   Data: JRC OpenACC database (Makridis et al. 2021), (c) European Union, CC BY 4.0,"
echo "   converted to NMEA sentences; see bags/README.md. Not endorsed by the JRC."
[ -f "$bag" ] || { echo "demo: no bag $bag" >&2; exit 1; }

work=$(mktemp -d "${TMPDIR:-/tmp}/acc_demo.XXXXXX")
export ROS_MASTER_URI=http://localhost:$port
export ROS_LOG_DIR=${ROS_LOG_DIR:-$work/log}
pids=()
cleanup() {
  # Our own processes only, newest first, by pid: SIGINT lets roslaunch stop its nodes.
  local i
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill -INT "${pids[i]}" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
  done
  [ -n "${DEMO_KEEP:-}" ] || rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

roscore -p "$port" > "$work/roscore.log" 2>&1 &
pids+=($!)
for _ in $(seq 100); do rostopic list > /dev/null 2>&1 && break; sleep 0.1; done
rostopic list > /dev/null 2>&1 || { echo "demo: roscore on port $port did not start" >&2; exit 1; }
rosparam set /use_sim_time true

python3 "$here/demo_listener.py" live &
pids+=($!)
# The recorder itself (rosrun execs it), not the `rosbag record` wrapper: Debian's wrapper dies in
# its SIGINT handler and returns before the recorder has closed the bag.
rosrun rosbag record --quiet -O "$work/out.bag" /relative_state /acc_parameters > "$work/record.log" 2>&1 &
recorder_pid=$!
pids+=($recorder_pid)
roslaunch acc_identification replay.launch bag:="$bag" rate:="$rate" window_s:="$window_s" \
  period_s:="$period_s" > "$work/launch.log" 2>&1 &
launch_pid=$!
pids+=($launch_pid)

# The player appears, plays, and exits at the end of the bag.
for _ in $(seq 300); do rosnode list 2>/dev/null | grep -qx /play && break; sleep 0.1; done
# rosnode list may time out under load: the player is gone after three misses in a row.
misses=0
while [ "$misses" -lt 3 ]; do
  kill -0 "$launch_pid" 2>/dev/null || { tail -n 30 "$work/launch.log" >&2; exit 1; }
  if rosnode list 2>/dev/null | grep -qx /play; then misses=0; else misses=$((misses + 1)); fi
  sleep 0.5
done
# The last epoch completes after 1 s of silence. Then /clock runs on past one more period, so the
# identifier's last window holds every sample, and a solve started on it finishes.
sleep 1.5
python3 "$here/demo_listener.py" advance "$(python3 -c "print(float('$period_s') + 2)")"
sleep 3
kill -INT "$launch_pid"; wait "$launch_pid" 2>/dev/null || true
sleep 1
kill -INT "$recorder_pid"; wait "$recorder_pid" 2>/dev/null || true  # the recorder closes its bag
for _ in $(seq 100); do [ -f "$work/out.bag" ] && break; sleep 0.1; done
[ -f "$work/out.bag" ] || { echo "demo: the recorder left no bag" >&2; tail -n 20 "$work/record.log" >&2; exit 1; }

echo
echo "== Summary: the identifier's last window next to a batch calibrate of the same samples =="
window=$(python3 "$here/demo_listener.py" last "$work/out.bag" "$work/online.json")
read -r start end <<< "$window"
rosbag filter "$work/out.bag" "$work/window.bag" \
  "topic == '/relative_state' and $start - 1e-6 <= m.header.stamp.to_sec() <= $end + 1e-6" > /dev/null
rosrun acc_identification calibrate --quiet --json "$work/batch.json" "$work/window.bag" 2>&1 | sed 's/^/   calibrate: /'
python3 "$here/demo_listener.py" compare "$work/online.json" "$work/batch.json"
