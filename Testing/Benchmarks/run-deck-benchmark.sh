#!/usr/bin/env bash
# The structural deck benchmark (issue 55, point 10): reading and writing an Abaqus/CalculiX deck of
# about 1M nodes (C3D10) against meshio (python3-meshio) on the same file, and a further variant of
# it (a design variable set, MLS Deform's update with the FEM verdict, the variant deck written).
#
# The deck is Examples/Structural/plate.py's plate with two holes, meshed by Gmsh (--nodes 1M: mesh
# size 0.062, about 1M nodes, built once and cached in the build folder, a few minutes; small: mesh
# size 0.3, seconds). Each figure is the median of --runs runs (default 3), with OMP_NUM_THREADS 1
# and 2 (--threads), in Debian's python3 with the plugin's folder on sys.path (the VTK classes
# mlsdeform.meshfile and the design of experiments use). Prints the machine, a table, the targets
# (read and write at least as fast as meshio; a further variant within 1 s on 2 threads) met or not,
# and a JSON line per thread count (DECKBENCHMARK ...).
#
# Usage: Testing/Benchmarks/run-deck-benchmark.sh [--nodes small|1M] [--runs N] [--threads "1 2"]
# Environment: MLSDEFORM_BUILD (default build/), MLSDEFORM_PLUGIN (the plugin .so).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
size=1M
runs=3
threads="1 2"
while (($#)); do
  case "$1" in
    --nodes) size=${2:?--nodes small|1M}; shift 2 ;;
    --runs) runs=${2:?--runs N}; shift 2 ;;
    --threads) threads=${2:?--threads LIST}; shift 2 ;;
    -h|--help) sed -n '2,/^set -e/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown argument $1 (--nodes small|1M, --runs N, --threads LIST)" >&2; exit 2 ;;
  esac
done
build=${MLSDEFORM_BUILD:-$root/build}
plugin=${MLSDEFORM_PLUGIN:-$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so}
[ -f "$plugin" ] || bash "$root/Testing/setup.sh"
/usr/bin/python3 -c 'import meshio' 2>/dev/null || bash "$root/Testing/setup.sh"
work=$build/deck-benchmark
deck=$(bash "$root/Testing/Benchmarks/structural/cached-plate.sh" "$size" "$build")
echo "Machine: $(lscpu | sed -n 's/^Model name: *//p'); $(nproc) CPUs; $(lscpu | sed -n 's/^Core(s) per socket: */cores per socket /p'), $(lscpu | sed -n 's/^Thread(s) per core: */threads per core /p')"
echo "Deck: $deck ($(du -h "$(dirname "$deck")/mesh.inp" | cut -f1) mesh file), medians of $runs runs"
lines=()
for t in $threads; do
  line=$(OMP_NUM_THREADS=$t /usr/bin/python3 "$root/Testing/Benchmarks/structural/deck_benchmark.py" "$(dirname "$plugin")" "$deck" "$runs" "$work/out" 2>/dev/null | grep '^DECKBENCHMARK ')
  echo "$line"
  lines+=("$line")
done
printf '%s\n' "${lines[@]}" | /usr/bin/python3 -c '
import json, sys
rows = [json.loads(line.split(" ", 1)[1]) for line in sys.stdin if line.strip()]
first = rows[0]
print("nodes %d, C3D10 elements %d" % (first["nodes"], first["elements"]))
print("| threads | read (ours) | read (meshio) | write (ours) | write (meshio) | first deformation (set-up) | further variant (deform, verdict, write) |")
print("|---|---|---|---|---|---|---|")
for r in rows:
    print("| %d | %.2f s | %.2f s | %.2f s | %.2f s | %.2f s | %.2f s |" % (r["threads"], r["read"], r["meshio_read"], r["write"], r["meshio_write"], r["first"], r["variant"]))
for r in rows:
    print("targets, %d thread(s): read %s meshio (%.1fx), write %s meshio (%.1fx)%s; every variant passes the FEM verdict: %s" % (
        r["threads"], "at least as fast as" if r["read"] <= r["meshio_read"] else "SLOWER than", r["meshio_read"] / r["read"],
        "at least as fast as" if r["write"] <= r["meshio_write"] else "SLOWER than", r["meshio_write"] / r["write"],
        ("; further variant %.2f s: %s" % (r["variant"], "within 1 s" if r["variant"] <= 1.0 else "OVER 1 s")) if r["threads"] == 2 else "",
        r["variants_pass"]))
'
