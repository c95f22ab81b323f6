#!/usr/bin/env bash
# Handle motions per second on the fandisk (issue 13's >= 10 updates per second while dragging),
# with 1 and 2 threads: region update, re-solve and offscreen render per motion. Sets up and
# builds first if needed.
# Usage: Testing/Benchmarks/run-handle-update-benchmark.sh [updates]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${MLSDEFORM_BUILD:-$root/build}
bash "$root/Testing/setup.sh" > /dev/null
# Debian's pvpython renders through X: on a machine without a display, a virtual one (xvfb).
on_display() { if [ -n "${DISPLAY:-}" ]; then "$@"; else xvfb-run -a -s "-screen 0 1024x768x24" "$@"; fi; }
for threads in 1 2; do
  echo -n "$threads thread(s): "
  OMP_NUM_THREADS=$threads on_display pvpython --no-mpi "$root/Testing/Benchmarks/handle_update_rate.py" \
    "$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so" "$build/data/fandisk.off" "${1:-60}" 2>&1 | tail -1
done
