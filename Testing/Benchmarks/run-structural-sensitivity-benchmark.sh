#!/usr/bin/env bash
# The exact structural shape gradient against a ccx solve (issue 65, point 6): on the plate of
# run-deck-benchmark.sh (C3D10, --nodes 1M: about 1M nodes, 300k, or small), the static step's
# displacements written in full precision (*NODE FILE, DOUBLE), one ccx run timed (OMP_NUM_THREADS 2,
# its solver's threads), then dJ/dX of the compliance at every node by vtkCalculixSensitivity (the
# deck and the .frd read, every element's derivative) with OMP_NUM_THREADS 1 and 2 (--threads),
# medians of --runs runs (default 3). Prints the machine, a table, the target (dJ/dX within the time
# of the ccx solve on 2 threads) met or not, and a JSON line per thread count (STRUCTSENS ...).
#
# Usage: Testing/Benchmarks/run-structural-sensitivity-benchmark.sh [--nodes small|300k|1M] [--runs N] [--threads "1 2"]
# Environment: MLSDEFORM_BUILD (default build/), MLSDEFORM_PLUGIN (the plugin .so).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
size=1M
runs=3
threads="1 2"
while (($#)); do
  case "$1" in
    --nodes) size=${2:?--nodes small|300k|1M}; shift 2 ;;
    --runs) runs=${2:?--runs N}; shift 2 ;;
    --threads) threads=${2:?--threads LIST}; shift 2 ;;
    -h|--help) sed -n '2,/^set -e/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown argument $1 (--nodes small|300k|1M, --runs N, --threads LIST)" >&2; exit 2 ;;
  esac
done
build=${MLSDEFORM_BUILD:-$root/build}
plugin=${MLSDEFORM_PLUGIN:-$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so}
[ -f "$plugin" ] || bash "$root/Testing/setup.sh"
command -v ccx > /dev/null || bash "$root/Testing/setup.sh"
# the deck benchmark's cached plate (the same mesh sizes)
source=$(dirname "$(bash "$root/Testing/Benchmarks/structural/cached-plate.sh" "$size" "$build")")
work=$build/structural-sensitivity-benchmark/$size
rm -rf "$work"
mkdir -p "$work"
cp "$source/mesh.inp" "$work/"
sed 's/^\*NODE FILE$/*NODE FILE, DOUBLE/' "$source/plate.inp" > "$work/plate.inp"
echo "Machine: $(lscpu | sed -n 's/^Model name: *//p'); $(nproc) CPUs; $(lscpu | sed -n 's/^Core(s) per socket: */cores per socket /p'), $(lscpu | sed -n 's/^Thread(s) per core: */threads per core /p')"
echo "Deck: $work/plate.inp ($(grep -c . "$work/mesh.inp") lines of mesh); ccx ..."
began=$(date +%s.%N)
(cd "$work" && OMP_NUM_THREADS=2 ccx -i plate > ccx.log 2>&1) || { tail -20 "$work/ccx.log"; exit 1; }
ccx_s=$(echo "$(date +%s.%N) - $began" | bc)
lines=()
for t in $threads; do
  line=$(OMP_NUM_THREADS=$t /usr/bin/python3 "$root/Testing/Benchmarks/structural/sensitivity_benchmark.py" "$(dirname "$plugin")" "$work/plate.inp" "$runs" | grep '^STRUCTSENS ')
  echo "$line"
  lines+=("$line")
done
printf '%s\n' "${lines[@]}" | CCX_S=$ccx_s /usr/bin/python3 -c '
import json, os, sys
rows = [json.loads(line.split(" ", 1)[1]) for line in sys.stdin if line.strip()]
ccx = float(os.environ["CCX_S"])
print("nodes %d; one ccx run (read, static solve, write; OMP_NUM_THREADS=2): %.2f s" % (rows[0]["nodes"], ccx))
print("| threads | dJ/dX of the compliance, every node (median) | / ccx run |")
print("|---|---|---|")
for r in rows:
    print("| %d | %.2f s | %.2fx |" % (r["threads"], r["median_s"], r["median_s"] / ccx))
for r in rows:
    if r["threads"] == 2:
        print("target, 2 threads: dJ/dX %.2f s %s the ccx run %.2f s" % (r["median_s"], "within" if r["median_s"] <= ccx else "NOT within", ccx))
'
