#!/usr/bin/env bash
# Constraint functions with many local variables (issue 66 point 3) on the OpenFOAM benchmark's
# case "DTC hull in a box" (built once by openfoam/make-hull-case.sh and cached, as for
# run-sensitivity-benchmark.sh). For each thread count, one pvpython --no-mpi process
# (constraint_benchmark.py) with 100 local variables on the hull and the constraints of an
# optimization times, median of --runs runs: a further variant, reverse mode dJ/dp, every
# geometric constraint's values and gradients, and the KS mesh quality with its gradient; then one
# process with the sensitivity benchmark's 6 body variables for the memory baseline. Prints the
# tables (the ratios against the targets: dJ/dp plus the constraints' gradients <= 0.5 of a
# variant, the mesh quality with its gradient <= 1 variant, peak memory <= 1.2 x the 6 variables')
# and JSON lines (CONSBENCH ...).
#
# Usage: Testing/Benchmarks/run-constraint-benchmark.sh [--cells small|400k|1M] [--runs N] [--threads "1 2"] [--variables N]
# (defaults: 1M cells, 5 runs, OMP_NUM_THREADS 1 then 2, 100 local variables.)
# Environment: MLSDEFORM_BUILD, MLSDEFORM_PLUGIN, MLSDEFORM_BENCHMARK_DIR, SNAPPY_RANKS as for
# run-sensitivity-benchmark.sh.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
here=$root/Testing/Benchmarks/openfoam
size=1M
runs=5
threads="1 2"
variables=100
while (($#)); do
  case "$1" in
    --cells) size=${2:?--cells small|400k|1M}; shift 2 ;;
    --runs) runs=${2:?--runs N}; shift 2 ;;
    --threads) threads=${2:?--threads "1 2"}; shift 2 ;;
    --variables) variables=${2:?--variables N}; shift 2 ;;
    -h|--help) sed -n '2,/^set -e/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown argument $1 (--cells small|400k|1M, --runs N, --threads LIST, --variables N)" >&2; exit 2 ;;
  esac
done
case "$size" in small|400k|1M) ;; *) echo "--cells small, 400k or 1M" >&2; exit 2 ;; esac
name=constraints
source "$root/Testing/Benchmarks/hull-run.sh"
bench() { # threads variables
  OMP_NUM_THREADS=$1 LD_LIBRARY_PATH=$plugin_path pvpython --no-mpi "$root/Testing/Benchmarks/constraint_benchmark.py" \
    "$run/plugin/$(basename "$plugin")" "$root/Examples/OpenFOAM" "$case/case.foam" "$runs" "$2" > "$run/threads-$1-$2.log" 2>&1 ||
    { tail -30 "$run/threads-$1-$2.log"; exit 1; }
  grep -E '^(Constraint benchmark|set-up|\||CONSBENCH)' "$run/threads-$1-$2.log"
}
for t in $threads; do
  echo "OMP_NUM_THREADS=$t (load $(cut -d' ' -f1-3 /proc/loadavg))"
  bench "$t" "$variables"
done
last=${threads##* }
echo "Memory baseline: the 6 body variables, OMP_NUM_THREADS=$last"
bench "$last" 6
peak() { sed -n 's/.*"peak_mib": \([0-9.]*\).*/\1/p' "$run/threads-$last-$1.log"; }
python3 -c "import sys; a, b = float(sys.argv[1]), float(sys.argv[2]); r = a / b
print('peak memory: %.0f MiB with %s local variables and the constraints, %.0f MiB with 6 body variables: %.2f x (<= 1.2) %s'
      % (a, sys.argv[3], b, r, 'met' if r <= 1.2 else 'NOT MET'))" "$(peak "$variables")" "$(peak 6)" "$variables"
echo "Plugin: a copy of $plugin built $built (sources $(git -C "$root" describe --always --dirty 2>/dev/null || echo '?') now); runs in $run"
