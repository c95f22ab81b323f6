#!/usr/bin/env bash
# Runs the deformation benchmark over generated surfaces of 10k to 1M points and k = 1k to 10k,
# one process per configuration, and prints one JSON line each (set-up time, median time of a
# variation = new handle motion on 1 and on 2 threads side by side, page faults per variation,
# peak memory). Sets up and builds first if needed.
# Usage: Testing/Benchmarks/run-benchmarks.sh [quick]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${MLSDEFORM_BUILD:-$root/build}
bash "$root/Testing/setup.sh" > /dev/null
bench="$build/Testing/Benchmarks/BenchmarkDeformation"
if [ "${1:-}" = quick ]; then
  configurations="10000:1000 100000:1000 100000:4000"
else
  configurations="10000:1000 100000:1000 465000:4000 1000000:1000 1000000:4000 100000:10000 1000000:10000"
fi
for configuration in $configurations; do
  "$bench" "${configuration%%:*}" "${configuration##*:}" 7
done
