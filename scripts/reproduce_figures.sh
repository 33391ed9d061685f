#!/usr/bin/env bash
# Reproduces the figures of Gunter et al. (issue 7): runs the `platoon` tool for each figure, then
# scripts/plot_figures.py, and prints the key numbers. With the catkin workspace sourced:
#   scripts/reproduce_figures.sh [DATA_DIR] [FIGURE_DIR]
# DATA_DIR (default build/figures_data) receives the CSV/JSON/log of each figure; FIGURE_DIR
# (default docs/figures) the PNGs. Environment:
#   PLATOON=path      the tool (default: rosrun acc_identification platoon)
#   RUNS_DIR=dir      OpenACC/canonical runs for Figs. 3-5 (default: the Casale runs shipped in
#                     data/openacc/casale.tar.xz, unpacked by scripts/bundled_data.sh)
#   TIMESERIES_RUN=f  the run of Figs. 3/4 (default RUNS_DIR/part6.csv)
#   CALIBRATION=f.json  a calibrate JSON of those runs, added to Figs. 3-5 (and 6-8 when
#                     ALL_FIGURES_CALIBRATION=1). Unset: when the calibrate tool is built, the
#                     script calibrates RUNS_DIR's part*.csv itself (--split half, as the paper)
#                     into DATA_DIR/nexo_min_calibrated.json; else Figs. 3-5 show Table II only.
set -eo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(dirname "$here")
data=${1:-$repo/build/figures_data}
figures=${2:-$repo/docs/figures}
source "$here/bundled_data.sh"
runs_dir=${RUNS_DIR:-$(bundled_openacc_dir casale)}
timeseries_run=${TIMESERIES_RUN:-$runs_dir/part6.csv}
mkdir -p "$data" "$figures"

platoon() {
  if [ -n "$PLATOON" ]; then "$PLATOON" "$@"; else rosrun acc_identification platoon "$@"; fi
}

# run NAME FIGURE ARGS...: one figure's data, its printed numbers kept in NAME.txt.
run() {
  local name=$1
  shift
  echo "== $name: platoon $*"
  platoon "$@" --csv "$data/$name.csv" --summary-json "$data/$name.json" 2>&1 | tee "$data/$name.txt"
}

calibrate() {
  if [ -n "$PLATOON" ]; then "$(dirname "$PLATOON")/calibrate" "$@"; else rosrun acc_identification calibrate "$@"; fi
}

if [ -z "$CALIBRATION" ] && [ -d "$runs_dir" ] && calibrate --help > /dev/null 2>&1; then
  CALIBRATION=$data/nexo_min_calibrated.json
  echo "== calibrate --split half $runs_dir/part*.csv"
  calibrate --split half --quiet --json "$CALIBRATION" "$runs_dir"/part*.csv 2>&1 | tee "$data/calibration.txt"
fi
calibration=()
[ -n "$CALIBRATION" ] && calibration=(--params "$CALIBRATION")
model_calibration=()
[ "${ALL_FIGURES_CALIBRATION:-0}" = 1 ] && model_calibration=("${calibration[@]}")
paper=(--setting min --setting max)

run fig1 lambda2-map --map-tau-e 0.5,1,1.5,2,3 --grid 100
run fig2 step --setting fig2-unstable --setting fig2-stable --vehicles 9
run fig6 bode "${paper[@]}" "${model_calibration[@]}"
run fig7 sinusoid "${paper[@]}" "${model_calibration[@]}" --vehicles 10 --frequency 0.204
run fig8 lead-profile "${paper[@]}" "${model_calibration[@]}" --profile I --vehicles 60 --short-platoon 15
# Profile I's ramps are an assumption (the paper gives none): how Fig. 8's numbers depend on them.
for ramp in "0.5 0.5" "1.0 1.0" "1.5 2.0" "2.5 3.5" "3.0 6.0"; do
  set -- $ramp
  echo "== fig8, maximum setting, lead ramps +$1/-$2 m/s^2"
  platoon lead-profile --setting max --profile I --vehicles 80 --lead-accel "$1" --lead-decel "$2" \
    --csv "$data/fig8_ramp.csv" --summary-json "$data/fig8_ramp_${1}_${2}.json" > "$data/fig8_ramp_${1}_${2}.txt"
  grep -E "drop below|by " "$data/fig8_ramp_${1}_${2}.txt"
done
rm -f "$data/fig8_ramp.csv"
if [ -d "$runs_dir" ]; then
  run_args=()
  for f in "$runs_dir"/part*.csv; do run_args+=(--run "$f"); done
  run fig5 equilibrium "${run_args[@]}" "${paper[@]}" "${calibration[@]}"
  run fig3 timeseries --run "$timeseries_run" "${paper[@]}" "${calibration[@]}"
else
  echo "no runs in $runs_dir: Figs. 3-5 skipped"
fi
/usr/bin/python3 "$here/plot_figures.py" "$data" "$figures"
