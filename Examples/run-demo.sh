#!/usr/bin/env bash
# The main job: sets up and builds if needed (Testing/setup.sh), then deforms the fandisk part
# (fixed base, handle moved sideways) and writes out/fandisk_deformed.vtp and out/fandisk_deformed.png.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${MLSDEFORM_BUILD:-$root/build}
bash "$root/Testing/setup.sh"
# -noreset: an X server resets when its last client disconnects; a client connecting meanwhile fails.
xvfb-run -a -s "-screen 0 1600x1200x24 -noreset" pvbatch "$root/Examples/deform_fandisk.py" \
  "$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so" "$build/data/fandisk.off" "${1:-$root/out}"
