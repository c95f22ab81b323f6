#!/usr/bin/env bash
# The paper's comparisons (Fig. 3, 4, 12, 13): sets up and builds if needed (Testing/setup.sh),
# then writes CSV files, PNG plots and report.md into the folder given (default out/comparisons).
# Pass --quick after the folder for the short version the test suite runs (about a minute).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${MLSDEFORM_BUILD:-$root/build}
bash "$root/Testing/setup.sh"
pvbatch "$root/Examples/paper_comparisons.py" "$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so" \
  "$build/data/fandisk.off" "${1:-$root/out/comparisons}" "${@:2}"
