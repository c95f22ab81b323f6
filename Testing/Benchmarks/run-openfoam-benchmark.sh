#!/usr/bin/env bash
# MLS Deform against OpenFOAM's moveMesh on the same case and motion (issue 12, point 6).
#
# Builds once (cached) the case "DTC hull in a box" (Testing/Benchmarks/openfoam/hullBox: the DTC
# hull of Debian's openfoam-examples, snappyHexMesh with 2 boundary layers; small: 53k cells,
# 63k points, 20 s to build; 1M: 1.08M cells, 1.19M points, 10 min to build on one core), then
# moves the hull by (0.25, 0, 0.1) m, inlet and outlet fixed,
# the sides (sideYmin, sideYmax), bottom and top slipping:
#   (a) moveMesh (displacementLaplacian, inverseDistance diffusivity from the hull) on a copy of
#       the case, timed with /usr/bin/time -v, then checkMesh on the moved mesh;
#   (b) pvpython --no-mpi (a serial run, as moveMesh's; MPI's start-up costs 0.35 s) with the
#       plugin (Examples/OpenFOAM/openfoam_variant.py: open_case, morph, save_variant), read ->
#       deform -> write, timed with /usr/bin/time -v, followed in the same
#       process by 2 further variants (new hull translations: solve + write only), then checkMesh
#       on each variant. compare_motion.py then checks that both moved the hull alike. The
#       table's MLS Deform wall time is the process's less the further
#       variants' (timed inside it); its peak RSS is the whole process's.
# Prints a side-by-side table (wall time, peak RSS, checkMesh figures) and the ratios against the
# issue's targets, and a JSON line (OPENFOAMBENCH ...) with every figure. Median of --runs runs
# (default 3 for small, 1 for 1M), the two tools' runs alternating; the first variant's ratio is
# also printed run by run (each pair ran back to back).
#
# Usage: Testing/Benchmarks/run-openfoam-benchmark.sh [--cells small|400k|1M] [--runs N] [--set NAME=VALUE ...]
# (--set: an MLS Deform property other than its default, e.g. --set MeshQuality=0.)
# Environment: MLSDEFORM_BUILD (build folder, default build/), MLSDEFORM_PLUGIN (the plugin,
# default in the build folder; if missing, Testing/setup.sh sets up and builds),
# MLSDEFORM_BENCHMARK_DIR (work folder holding the cached cases and the runs, default
# $MLSDEFORM_BUILD/openfoam-benchmark), SNAPPY_RANKS (MPI ranks of snappyHexMesh, default 1:
# on 2 shared cores 2 ranks were slower, 80 s against 20 s on the small case).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
here=$root/Testing/Benchmarks/openfoam
size=small
runs=
settings=()
while (($#)); do
  case "$1" in
    --cells) size=${2:?--cells small|400k|1M}; shift 2 ;;
    --runs) runs=${2:?--runs N}; shift 2 ;;
    --set) settings+=(--set "${2:?--set NAME=VALUE}"); shift 2 ;;
    -h|--help) sed -n '2,/^set -e/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown argument $1 (--cells small|400k|1M, --runs N, --set NAME=VALUE)" >&2; exit 2 ;;
  esac
done
case "$size" in small) runs=${runs:-3} ;; 400k|1M) runs=${runs:-1} ;; *) echo "--cells small, 400k or 1M" >&2; exit 2 ;; esac
build=${MLSDEFORM_BUILD:-$root/build}
plugin=${MLSDEFORM_PLUGIN:-$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so}
work=${MLSDEFORM_BENCHMARK_DIR:-$build/openfoam-benchmark}
[ -f "$plugin" ] || bash "$root/Testing/setup.sh"
command -v snappyHexMesh > /dev/null || [ -x /usr/bin/snappyHexMesh ] || bash "$root/Testing/setup.sh"
[ -x /usr/bin/time ] || { echo "/usr/bin/time is needed (Debian package time)" >&2; exit 1; }
mkdir -p "$work"
work=$(cd "$work" && pwd)

motion=(0.25 0 0.1)                  # the hull's translation, both tools [m]
further=("0.1,0,-0.1" "-0.2,0.05,0.05") # MLS Deform's further variants

# The case, built once (cached in the work folder, shared by the benchmarks).
case=$(bash "$here/cached-hull-case.sh" "$size" "$work")

set +u
source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1
set -u
run=$work/run-$size
rm -rf "$run"
mkdir -p "$run"
# A copy of the plugin's folder, so that a rebuild during the runs does not mix builds; its
# libraries are found first through LD_LIBRARY_PATH (the plugin's RUNPATH names the build folder).
built=$(date -r "$plugin" '+%F %T')
cp -r "$(dirname "$plugin")" "$run/plugin"
plugin_path=$run/plugin${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
cp "$case/log.checkMesh" "$run/checkMesh.source"
load() { cut -d' ' -f1-3 /proc/loadavg; }
copy_case() { # a copy of the case without its logs
  rm -rf "$1"
  mkdir -p "$1"
  cp -r "$case/0" "$case/constant" "$case/system" "$1/"
  touch "$1/case.foam"
}

# The runs alternate (moveMesh, MLS Deform, moveMesh, ...) so that a change in the machine's speed
# during the benchmark (other load, a neighbour on a shared host) weighs on both alike.
for ((i = 1; i <= runs; i++)); do
  echo "moveMesh run $i/$runs (load $(load))"
  copy_case "$run/moveMesh"
  foamDictionary -entry boundaryField/hull/value -set "uniform (${motion[*]})" "$run/moveMesh/0/pointDisplacement" > /dev/null
  (cd "$run/moveMesh" && /usr/bin/time -v -o "$run/moveMesh-$i.time" moveMesh > "$run/moveMesh-$i.log" 2>&1) ||
    { tail -30 "$run/moveMesh-$i.log"; exit 1; }
  echo "MLS Deform run $i/$runs (load $(load))"
  rm -rf "$run/mls"
  LD_LIBRARY_PATH=$plugin_path /usr/bin/time -v -o "$run/mls-$i.time" pvpython --no-mpi "$here/mls_benchmark.py" "$run/plugin/$(basename "$plugin")" "$root/Examples/OpenFOAM" \
    "$case/case.foam" "$run/mls" ${settings[@]+"${settings[@]}"} "$(IFS=,; echo "${motion[*]}")" "${further[@]}" \
    > "$run/mls-$i.log" 2>&1 ||
    { tail -30 "$run/mls-$i.log"; exit 1; }
done
(cd "$run/moveMesh" && checkMesh -latestTime > "$run/checkMesh.moveMesh" 2>&1) || true
(cd "$run/mls/variant-0" && checkMesh > "$run/checkMesh.mls" 2>&1) || true
for ((v = 1; v <= ${#further[@]}; v++)); do
  (cd "$run/mls/variant-$v" && checkMesh > "$run/checkMesh.mls-$v" 2>&1) || true
done

pvpython "$here/compare_motion.py" "$case" "$run/moveMesh" "$run/mls/variant-0" "$(IFS=,; echo "${motion[*]}")" \
  > "$run/motion.txt" 2>&1 || true

python3 "$here/report.py" "$run" "$size"
echo "Plugin: a copy of $plugin built $built (sources $(git -C "$root" describe --always --dirty 2>/dev/null || echo '?') now); runs in $run"
