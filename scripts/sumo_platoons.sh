#!/bin/bash
# The ZalaZone platoons in SUMO, as docs/SUMO.md reports them: the campaign's vTypes (base and
# diagnosed), every platoon run replayed in SUMO with each, and the dips scored against the real
# cars (median dip error, median abs. error, links with the right growth or decay) and against the
# package's own chain of the same models.
#
# Usage: scripts/sumo_platoons.sh WORKSPACE [OUT_DIR] [DATA_DIR]
#   WORKSPACE  a catkin workspace built with the campaign and sumo components
#   OUT_DIR    default: a temporary folder (zalazone.add.xml, one JSON per run and mode)
#   DATA_DIR   default: the ZalaZone runs shipped in data/openacc/zalazone_dynamic.tar.xz
# Needs `sumo` (Debian's package). Data: JRC OpenACC database (Makridis et al., Transportation
# Research Part C 125 (2021) 103047), (c) European Union, CC BY 4.0.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
ws="${1:?usage: sumo_platoons.sh WORKSPACE [OUT_DIR] [DATA_DIR]}"
out="${2:-$(mktemp -d)}"
source "$here/scripts/bundled_data.sh"
data="${3:-$(bundled_openacc_dir zalazone_dynamic)}"
bin="$ws/devel/lib/acc_identification"
for tool in campaign sumo_replay; do
  [ -x "$bin/$tool" ] || { echo "error: $bin/$tool not built" >&2; exit 1; }
done
mkdir -p "$out"
"$bin/campaign" --quiet --threads 2 --sumo-vtype "$out/zalazone.add.xml" "$data" > "$out/campaign.txt"
for run in "$data"/*.csv; do
  name=$(basename "$run" .csv)
  for mode in base diagnosed; do
    flag=()
    [ "$mode" = diagnosed ] && flag=(--diagnosed)
    # A run whose chain cannot start (its first follower has no vType) is said in its log and
    # leaves no JSON; the summary counts what was replayed.
    "$bin/sumo_replay" --platoon "$run" --vtype "$out/zalazone.add.xml" "${flag[@]}" \
      --json "$out/${name}_$mode.json" > "$out/${name}_$mode.txt" 2>&1 || rm -f "$out/${name}_$mode.json"
  done
done
/usr/bin/python3 - "$out" <<'EOF'
import glob, json, os, statistics, sys
out = sys.argv[1]
for mode in ("base", "diagnosed"):
    errors, model_errors, apart, links, runs = [], [], [], [], 0
    for path in sorted(glob.glob(os.path.join(out, "*_%s.json" % mode))):
        runs += 1
        for segment in json.load(open(path))["segments"]:
            for perturbation in segment["perturbations"]:
                previous_measured = previous_sumo = perturbation["leader_dip_mps"]
                for p in perturbation["positions"]:
                    measured, sumo, model = p.get("measured_dip_mps"), p.get("sumo_dip_mps"), p.get("model_dip_mps")
                    if measured is None or sumo is None:
                        continue
                    errors.append((sumo - measured) / measured)
                    if model is not None:
                        model_errors.append((model - measured) / measured)
                        apart.append(abs(sumo - model))
                    links.append((measured > previous_measured) == (sumo > previous_sumo))
                    previous_measured, previous_sumo = measured, sumo
    if not errors:
        print("%s: nothing replayed" % mode)
        continue
    print("%-9s %d runs, %d car-perturbations: SUMO median dip error %+.0f %%, median abs. %.0f %%, growth/decay right "
          "%d of %d; package's chain of the same models %+.0f %%; SUMO against it median %.2f m/s, at most %.2f"
          % (mode, runs, len(errors), 100 * statistics.median(errors), 100 * statistics.median(abs(e) for e in errors),
             sum(links), len(links), 100 * statistics.median(model_errors), statistics.median(apart), max(apart)))
EOF
echo "files: $out"
