#!/usr/bin/env bash
# Two builds of the plugin on the same scenes, compared bitwise (issue 28 point 7: a refactoring
# changes no result).
#
# Each scene runs with each plugin in its own pvpython --no-mpi process (serial, nothing rendered)
# and saves every output of the plugin's filters; then every output point coordinate, the cells,
# every point, cell, field and table array (Displacement, residuals, constraint reports, ...; not
# the times SetupTime and SolveTime) and every file of the written OpenFOAM variant must be the
# same bits in both.
# Prints, per array, its values, how many differ and the largest absolute difference; the exit
# status is 1 if any differs (or exists in one run only). The scenes (compare_plugins.py):
#   fandisk              Examples/deform_fandisk.py, then on its pipeline a new handle motion
#                        (cached set-up, re-solved) and a new handle weight (refactorized)
#   fandisk-constrained  Examples/deform_fandisk_constrained.py (feature lines, planarity)
#   joint-primitives     Examples/deform_joint_primitives.py (Primitive Detector on the joint,
#                        deformations keeping its primitives)
#   fandisk-filters      Primitive Detector and MLS Sampler (both outputs) on fandisk, MLS Deform
#                        on the sampler's samples
#   openfoam             Examples/OpenFOAM/morph_case.py on the sphereChannel case (built here by
#                        Examples/OpenFOAM/make-case.sh, 3 s) and its variant case's files,
#                        Deformation Quality of the internal mesh (a volume mesh) against the original
# The example scripts run as users run them (runpy), their pictures skipped. About a minute.
#
# Usage: Testing/Benchmarks/compare-plugins.sh [A [B]] [--scene NAME ...]
#   A: the reference plugin's MLSDeform.so (default $MLSDEFORM_BASELINE_PLUGIN, e.g. a copy of the
#      plugin's folder made before a refactoring), B: the plugin to check (default the build's).
#   Each plugin's folder is copied first (a rebuild during the runs cannot mix builds) and put
#   first in LD_LIBRARY_PATH (the plugin's RUNPATH names the build folder it was built in).
# Environment: MLSDEFORM_BUILD (build folder, default build/; CMake puts fandisk.off and joint.off
# in its data/), MLSDEFORM_COMPARE_DIR (work folder, emptied first, default
# $MLSDEFORM_BUILD/compare-plugins: A/ and B/ hold each scene's outputs and log).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${MLSDEFORM_BUILD:-$root/build}
plugins=()
scenes=()
while (($#)); do
  case "$1" in
    --scene) scenes+=("${2:?--scene NAME}"); shift 2 ;;
    -h|--help) sed -n '2,/^set -e/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) plugins+=("$1"); shift ;;
  esac
done
a=${plugins[0]:-${MLSDEFORM_BASELINE_PLUGIN:-}}
b=${plugins[1]:-$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so}
[ -n "$a" ] || { echo "usage: compare-plugins.sh A [B] (or set MLSDEFORM_BASELINE_PLUGIN)" >&2; exit 2; }
for plugin in "$a" "$b"; do
  [ -f "$plugin" ] || { echo "no plugin $plugin" >&2; exit 2; }
done
data=$build/data
[ -f "$data/fandisk.off" ] && [ -f "$data/joint.off" ] || { echo "no fandisk.off and joint.off in $data (CMake copies them from Debian's libcgal-demo)" >&2; exit 2; }
work=${MLSDEFORM_COMPARE_DIR:-$build/compare-plugins}
script=$root/Testing/Benchmarks/compare_plugins.py
export PYTHONDONTWRITEBYTECODE=1  # no __pycache__ in Examples/
((${#scenes[@]})) || read -r -a scenes <<< "$(pvpython --no-mpi "$script" scenes 2> /dev/null | tail -1)"

rm -rf "$work"
mkdir -p "$work"
work=$(cd "$work" && pwd)
declare -A plugin_of=([A]=$a [B]=$b)
for side in A B; do
  plugin=${plugin_of[$side]}
  mkdir -p "$work/$side"
  cp -r "$(dirname "$plugin")" "$work/$side/plugin"
  plugin_of[$side]=$work/$side/plugin/$(basename "$plugin")  # from here on, the copy
  echo "$side: $plugin (built $(date -r "$plugin" '+%F %T'))"
done
bash "$root/Examples/OpenFOAM/make-case.sh" "$work/sphereChannel" > "$work/make-case.log" 2>&1 ||
  { cat "$work/make-case.log"; exit 1; }

for scene in "${scenes[@]}"; do
  for side in A B; do
    log=$work/$side/$scene.log
    start=$SECONDS
    LD_LIBRARY_PATH=$work/$side/plugin${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH} \
      pvpython --no-mpi "$script" run "$scene" "${plugin_of[$side]}" "$data" \
      "$work/sphereChannel/case.foam" "$work/$side" > "$log" 2>&1 ||
      { tail -30 "$log"; echo "scene $scene failed with plugin $side (log: $log)" >&2; exit 1; }
    echo "$scene with $side: $(tail -1 "$log") in $((SECONDS - start)) s"
  done
done
pvpython --no-mpi "$script" compare "$work/A" "$work/B"
