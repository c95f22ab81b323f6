#!/usr/bin/env bash
# Writing a variant against copying the file, per format (issue 56, point 9): for each solver format a
# mesh of about --nodes nodes (default 1000000) made by a third-party writer (Gmsh, ParaView,
# OpenFOAM's foamMeshToFluent; built once into the build folder), the median of --runs runs (default
# 3) of copying it and of writing a variant with every node moved, with OMP_NUM_THREADS 1 and 2
# (--threads). Prints the machine, a table and a JSON line per format and thread count.
#
# Usage: Testing/Benchmarks/run-format-benchmark.sh [--nodes N] [--runs N] [--threads "1 2"]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
nodes=1000000
runs=3
threads="1 2"
while (($#)); do
  case "$1" in
    --nodes) nodes=${2:?--nodes N}; shift 2 ;;
    --runs) runs=${2:?--runs N}; shift 2 ;;
    --threads) threads=${2:?--threads LIST}; shift 2 ;;
    -h|--help) sed -n '2,/^set -e/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown argument $1 (--nodes N, --runs N, --threads LIST)" >&2; exit 2 ;;
  esac
done
build=${MLSDEFORM_BUILD:-$root/build}
plugin=${MLSDEFORM_PLUGIN:-$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so}
[ -f "$plugin" ] || bash "$root/Testing/setup.sh"
work=$build/format-benchmark-$nodes
echo "Machine: $(lscpu | sed -n 's/^Model name: *//p'); $(nproc) CPUs"
lines=()
for t in $threads; do
  while IFS= read -r line; do
    echo "$line"
    lines+=("$line (threads $t)")
  done < <(OMP_NUM_THREADS=$t pvpython "$root/Testing/Benchmarks/structural/format_benchmark.py" "$plugin" "$work" "$nodes" "$runs" 2>/dev/null | grep '^FORMATBENCHMARK ')
done
printf '%s\n' "${lines[@]}" | /usr/bin/python3 -c '
import json, sys
print("| format | nodes | file | threads | copy | variant | variant / copy |")
print("|---|---|---|---|---|---|---|")
for line in sys.stdin:
    body, threads = line.rsplit(" (threads ", 1)
    r = json.loads(body.split(" ", 1)[1])
    print("| %s | %d | %.0f MB | %s | %.2f s | %.2f s | %.1f |" % (r["format"], r["nodes"], r["bytes"] / 1e6, threads.rstrip(")\n"),
          r["copy"], r["variant"], r["variant"] / r["copy"]))
'
