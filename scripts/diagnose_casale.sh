#!/bin/bash
# Runs the sim-to-real gap diagnosis on the four OpenACC Casale runs (Hyundai Nexo on ACC,
# minimum distance setting) and writes the report that docs/DIAGNOSIS.md quotes.
#
# Usage: scripts/diagnose_casale.sh WORKSPACE [OUT_DIR] [DATA_DIR]
#   WORKSPACE  a catkin workspace built with the calibration and diagnosis components
#   OUT_DIR    default docs/diagnosis/casale (report.md, diagnosis.json, PNG figures)
#   DATA_DIR   default: the Casale runs shipped in data/openacc/casale.tar.xz (unpacked by
#              scripts/bundled_data.sh)
# Data: JRC OpenACC database (Makridis et al., Transportation Research Part C 125 (2021) 103047),
# (c) European Union, CC BY 4.0; the report carries the attribution.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
ws="${1:?usage: diagnose_casale.sh WORKSPACE [OUT_DIR] [DATA_DIR]}"
# Absolute: the tool runs from the data folder below, where a relative workspace would not resolve.
ws="$(cd "$ws" && pwd)" || { echo "error: no workspace at $1" >&2; exit 1; }
out="${2:-$here/docs/diagnosis/casale}"
source "$here/scripts/bundled_data.sh"
data="${3:-$(bundled_openacc_dir casale)}"
tool="$ws/devel/lib/acc_identification/diagnose"
[ -x "$tool" ] || { echo "error: $tool not built (build with ACC_COMPONENTS including calibration;diagnosis)" >&2; exit 1; }
runs=()
for part in part3 part4 part5 part6; do
  [ -r "$data/$part.csv" ] || { echo "error: $data/$part.csv missing" >&2; exit 1; }
  runs+=("$part.csv")
done
mkdir -p "$out"
out=$(cd "$out" && pwd)
# From the data folder, so that the report names its inputs part3.csv..., not this machine's paths.
(cd "$data" && "$tool" "${runs[@]}" --json "$out/diagnosis.json" --report "$out" \
  --plot-script "$here/scripts/plot_diagnosis.py")
# The per-sample tables behind the figures are large and fully reproducible from the data; the
# report, the JSON and the figures are what is kept.
rm -f "$out/residuals.csv" "$out/spectrum.csv" "$out/gain.csv" "$out/train_fit.csv"
echo "report: $out/report.md"
