#!/usr/bin/env bash
# Handle motions per second while dragging, with 1 and 2 threads (handle_update_rate.py): region
# update, re-solve and offscreen render per motion,
#   - on the fandisk (issue 13: >= 10 updates per second);
#   - on the benchmarks' OpenFOAM case "DTC hull in a box" (issue 32, point 7: >= 5 updates per
#     second on the 1M-cell case), the hull shown: a drag step moves the patches, the release the
#     internal mesh; the same steps moving the whole mesh beside them.
# Sets up and builds first if needed; the case is built once and cached (make-hull-case.sh: 10
# minutes for 1M).
# Usage: Testing/Benchmarks/run-handle-update-benchmark.sh [--cells small|400k|1M] [updates]
#   (default: 1M, 60 updates on the fandisk and 30 on the case)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${MLSDEFORM_BUILD:-$root/build}
size=1M
if [ "${1:-}" = "--cells" ]; then size=${2:?--cells small|400k|1M}; shift 2; fi
bash "$root/Testing/setup.sh" > /dev/null
plugin=$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so
case=$(bash "$root/Testing/Benchmarks/openfoam/cached-hull-case.sh" "$size" "${MLSDEFORM_BENCHMARK_DIR:-$build/openfoam-benchmark}")
echo "CPU: $(lscpu | sed -n 's/^Model name: *//p'); $(nproc) cores"
# Debian's pvpython renders through X: on a machine without a display, a virtual one (xvfb).
on_display() { if [ -n "${DISPLAY:-}" ]; then "$@"; else xvfb-run -a -s "-screen 0 1024x768x24" "$@"; fi; }
for threads in 1 2; do
  for input in "$build/data/fandisk.off:${1:-60}" "$case/case.foam:${1:-30}"; do
    echo -n "$threads thread(s), "
    OMP_NUM_THREADS=$threads on_display pvpython --no-mpi "$root/Testing/Benchmarks/handle_update_rate.py" \
      "$plugin" "${input%:*}" "${input##*:}" 2>&1 | tail -1
  done
done
