#!/usr/bin/env bash
# Exact constraints against the soft ones (issue 31, point 7), with 1 and 2 threads: set-up,
# median time of a variation, largest constraint residual.
#  - the fandisk scene of paper Fig. 8 (exact_constraints_benchmark.py), always;
#  - with --hull small|400k|1M, the cached "DTC hull in a box" case (run-openfoam-benchmark.sh
#    builds it): the bow moved, the hull's largest plane and cylinder behind it kept
#    (openfoam/constrained_hull.py).
# Sets up and builds first if needed.
# Usage: Testing/Benchmarks/run-exact-constraints-benchmark.sh [--variations N] [--hull small|400k|1M]
# Environment: MLSDEFORM_BUILD, MLSDEFORM_PLUGIN, MLSDEFORM_BENCHMARK_DIR as run-openfoam-benchmark.sh.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
variations=7
hull=
while (($#)); do
  case "$1" in
    --variations) variations=${2:?--variations N}; shift 2 ;;
    --hull) hull=${2:?--hull small|400k|1M}; shift 2 ;;
    *) echo "unknown argument $1 (--variations N, --hull small|400k|1M)" >&2; exit 2 ;;
  esac
done
build=${MLSDEFORM_BUILD:-$root/build}
plugin=${MLSDEFORM_PLUGIN:-$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so}
[ -f "$plugin" ] && [ -f "$build/data/fandisk.off" ] || bash "$root/Testing/setup.sh" > /dev/null
echo "Machine: $(lscpu | sed -n 's/^Model name: *//p'); $(nproc) CPUs"
for threads in 1 2; do
  OMP_NUM_THREADS=$threads pvbatch --no-mpi "$root/Testing/Benchmarks/exact_constraints_benchmark.py" \
    "$plugin" "$build/data/fandisk.off" "$root/Examples" "$variations" 2>&1 | grep '^{'
done
if [ -n "$hull" ]; then
  work=${MLSDEFORM_BENCHMARK_DIR:-$build/openfoam-benchmark}
  mkdir -p "$work"
  case=$(bash "$root/Testing/Benchmarks/openfoam/cached-hull-case.sh" "$hull" "$(cd "$work" && pwd)")
  echo "Case: $(grep -E '^ *cells:' "$case/log.checkMesh" | tr -s ' ') $(grep -E '^ *points:' "$case/log.checkMesh" | tr -s ' ')"
  for threads in 1 2; do
    OMP_NUM_THREADS=$threads /usr/bin/python3 "$root/Testing/Benchmarks/openfoam/constrained_hull.py" \
      "$(dirname "$plugin")" "$case/case.foam" "$((variations < 5 ? variations : 5))" 2>&1 | grep '^{'
  done
fi
