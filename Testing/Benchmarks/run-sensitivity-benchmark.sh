#!/usr/bin/env bash
# Design sensitivities on the OpenFOAM benchmark's case "DTC hull in a box" (the case of
# run-openfoam-benchmark.sh, built once by openfoam/make-hull-case.sh and cached in the same
# folder, so that either script reuses the other's case; 1M: 1.08M cells, 10 min to build).
# The hull is a Handle with six design variables (translate x, y, z, rotate about y and z, scale
# along x), the inlet and outlet are Fixed, the sides, bottom and top Slip. For each thread count,
# one pvpython --no-mpi process (sensitivity_benchmark.py) times, median of --runs runs: a further
# variant (setDesignVars + update), reverse mode dJ/dp (totalSensitivity, dJ/dX random on the
# hull's points) and forward mode (one totalSensitivityProd per variable), and prints a table with
# the ratios against the targets (reverse <= 20% of a further variant; forward for m variables
# <= m further variants), the check that both modes give the same dJ/dp, and a JSON line
# (SENSBENCH ...). Fails when the two modes disagree.
#
# Usage: Testing/Benchmarks/run-sensitivity-benchmark.sh [--cells small|400k|1M] [--runs N] [--threads "1 2"] [--set NAME=VALUE ...]
# (defaults: 1M cells, 5 runs, OMP_NUM_THREADS 1 then 2; --set: an MLS Deform property other
# than its default, e.g. --set MeshQuality=0.)
# Environment: MLSDEFORM_BUILD (build folder, default build/), MLSDEFORM_PLUGIN (the plugin,
# default in the build folder; if missing, Testing/setup.sh sets up and builds),
# MLSDEFORM_BENCHMARK_DIR (work folder holding the cached cases and the runs, default
# $MLSDEFORM_BUILD/openfoam-benchmark), SNAPPY_RANKS (MPI ranks of snappyHexMesh, default 1).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
here=$root/Testing/Benchmarks/openfoam
size=1M
runs=5
threads="1 2"
settings=()
while (($#)); do
  case "$1" in
    --cells) size=${2:?--cells small|400k|1M}; shift 2 ;;
    --runs) runs=${2:?--runs N}; shift 2 ;;
    --threads) threads=${2:?--threads "1 2"}; shift 2 ;;
    --set) settings+=(--set "${2:?--set NAME=VALUE}"); shift 2 ;;
    -h|--help) sed -n '2,/^set -e/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown argument $1 (--cells small|400k|1M, --runs N, --threads LIST, --set NAME=VALUE)" >&2; exit 2 ;;
  esac
done
case "$size" in small|400k|1M) ;; *) echo "--cells small, 400k or 1M" >&2; exit 2 ;; esac
name=sensitivity
source "$root/Testing/Benchmarks/hull-run.sh"
for t in $threads; do
  echo "OMP_NUM_THREADS=$t (load $(cut -d' ' -f1-3 /proc/loadavg))"
  OMP_NUM_THREADS=$t LD_LIBRARY_PATH=$plugin_path pvpython --no-mpi "$root/Testing/Benchmarks/sensitivity_benchmark.py" \
    "$run/plugin/$(basename "$plugin")" "$root/Examples/OpenFOAM" "$case/case.foam" "$runs" ${settings[@]+"${settings[@]}"} \
    > "$run/threads-$t.log" 2>&1 || { tail -30 "$run/threads-$t.log"; exit 1; }
  grep -E '^(Sensitivity benchmark|set-up|SensitivityMethod|\||check:|SENSBENCH)' "$run/threads-$t.log" # without VTK's messages
done
echo "Plugin: a copy of $plugin built $built (sources $(git -C "$root" describe --always --dirty 2>/dev/null || echo '?') now); runs in $run"
