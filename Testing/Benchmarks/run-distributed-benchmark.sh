#!/usr/bin/env bash
# Strong scaling of MLS Deform over MPI ranks (issue 14): the same ~1M-point tetrahedral box on 1
# and 2 ranks (pvbatch under mpiexec, one OpenMP thread per rank, so that 2 ranks use the 2 cores
# as 2 threads would), set-up and per-variation time and the peak memory of each rank. Sets up and
# builds first if needed.
# Usage: Testing/Benchmarks/run-distributed-benchmark.sh [SIZE (points per side, default 101)] [VARIATIONS (default 7)]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${MLSDEFORM_BUILD:-$root/build}
bash "$root/Testing/setup.sh" > /dev/null
plugin="$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so"
for ranks in 1 2; do
  echo "== $ranks rank(s)"
  OMP_NUM_THREADS=1 mpiexec --allow-run-as-root --oversubscribe -n "$ranks" \
    /usr/bin/time -f "peak memory of a rank: %M kB" \
    pvbatch "$root/Testing/Benchmarks/distributed_scaling.py" "$plugin" "${1:-101}" "${2:-7}" 2>&1 |
    grep -E '^\{|peak memory'
done
