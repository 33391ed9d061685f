#!/usr/bin/env bash
# The main job on the bundled default data. Run through `make demo`, with the workspace sourced.
set -eo pipefail
echo "== String stability of the paper's calibrated ACC settings (Gunter et al., Table II) =="
rosrun acc_identification stability_report
