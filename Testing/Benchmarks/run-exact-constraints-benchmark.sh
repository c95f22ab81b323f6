#!/usr/bin/env bash
# Exact constraints against the soft ones (issue 31) on the fandisk scene of paper Fig. 8, with 1
# and 2 threads: set-up, median time of a variation, largest constraint residual. Sets up and
# builds first if needed.
# Usage: Testing/Benchmarks/run-exact-constraints-benchmark.sh [variations]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${MLSDEFORM_BUILD:-$root/build}
bash "$root/Testing/setup.sh" > /dev/null
for threads in 1 2; do
  OMP_NUM_THREADS=$threads pvbatch --no-mpi "$root/Testing/Benchmarks/exact_constraints_benchmark.py" \
    "$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so" "$build/data/fandisk.off" "$root/Examples" "${1:-7}" 2>&1 | grep '^{'
done
