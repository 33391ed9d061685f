#!/usr/bin/env bash
# Regenerates every bag of bags/ deterministically (same tools, same bytes):
#   casale_partN_sentences.bag  raw NMEA of both receivers from the JRC OpenACC Casale runs
#                               part3, part4, part5 (part6, 25 minutes, would be 2 MB alone)
#   zalazone_toyota_rav4_s_sentences.bag
#                               raw NMEA of a Toyota RAV4 on ACC (setting S) and the Audi e-tron
#                               ahead of it in four perturbation runs of the JRC OpenACC ZalaZone
#                               campaign, laid end to end 20 s apart as one session
#   synthetic_min_F.bag         synthesize --profile F --setting min --seed 1 (+ truth CSV, JSON)
#   synthetic_max_F.bag         synthesize --profile F --setting max --seed 1 (+ truth CSV, JSON)
# Usage: scripts/make_bags.sh [WORKSPACE]   (default build/ws; the workspace must be built with
#        the gnss, relative_state, reproduction, diagnosis and synthesis components)
# OPENACC_DIR overrides where the OpenACC CSVs are (default: the Casale runs shipped in
# data/openacc/casale.tar.xz, unpacked by scripts/bundled_data.sh).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
ws=${1:-$repo/build/ws}
bin=$ws/devel/lib/acc_identification
source "$repo/scripts/bundled_data.sh"
openacc=${OPENACC_DIR:-$(bundled_openacc_dir casale)}
zalazone=${ZALAZONE_DIR:-$(bundled_openacc_dir zalazone_toyota_rav4_s)}
out=$repo/bags
for tool in openacc_to_nmea nmea_to_bag synthesize; do
  [ -x "$bin/$tool" ] || { echo "make_bags: $bin/$tool not built (see the usage in $0)" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Real data: OpenACC CSV -> two NMEA logs -> one bag of raw sentences per run.
for run in part3 part4 part5; do
  "$bin/openacc_to_nmea" "$openacc/$run.csv" "$work/${run}_leader.nmea" "$work/${run}_follower.nmea"
  "$bin/nmea_to_bag" "$work/${run}_leader.nmea" "$work/${run}_follower.nmea" "$out/casale_${run}_sentences.bag"
done

# Real perturbation runs of one car and setting (JRC OpenACC ZalaZone, the excerpt in
# data/openacc/zalazone_toyota_rav4_s.tar.xz): each run keeps its own clock, and the runs of one
# day overlap in it, so each is shifted to start 20 s after the previous one ends (a hole the
# chain counts as a dropout and the identifier as a split, never as data).
: > "$work/zalazone_leader.nmea"
: > "$work/zalazone_follower.nmea"
next_start_s=
for run in dynamic_part5 dynamic_part6 dynamic_part12 dynamic_part14; do
  csv=$zalazone/$run.csv
  first_s=$(sed -n 7p "$csv" | cut -d, -f1)
  last_s=$(tail -n 1 "$csv" | cut -d, -f1)
  shift_s=$(python3 -c "print(round((${next_start_s:-$first_s}) - $first_s, 3))")
  "$bin/openacc_to_nmea" --follower TOYOTA_RAV4 --time-shift-s "$shift_s" "$csv" \
    "$work/${run}_leader.nmea" "$work/${run}_follower.nmea"
  cat "$work/${run}_leader.nmea" >> "$work/zalazone_leader.nmea"
  cat "$work/${run}_follower.nmea" >> "$work/zalazone_follower.nmea"
  next_start_s=$(python3 -c "print(round($last_s + $shift_s + 20.0, 3))")
done
"$bin/nmea_to_bag" "$work/zalazone_leader.nmea" "$work/zalazone_follower.nmea" \
  "$out/zalazone_toyota_rav4_s_sentences.bag"

# Synthetic drives of profile F (about 430 s) for both settings of Table II.
for setting in min max; do
  "$bin/synthesize" --profile F --setting "$setting" --seed 1 \
    --leader-log "$work/${setting}_leader.nmea" --follower-log "$work/${setting}_follower.nmea" \
    --truth-csv "$out/synthetic_${setting}_F_truth.csv" \
    --parameters-json "$out/synthetic_${setting}_F_parameters.json" \
    --bag "$out/synthetic_${setting}_F.bag"
done
ls -la "$out"
