#!/usr/bin/env bash
# The benchmarks' case "DTC hull in a box" of the given size (small, 400k or 1M), built once in WORK
# (make-hull-case.sh) and rebuilt when the template (hullBox/) changed. Prints the case's folder;
# what it does goes to stderr. Environment: SNAPPY_RANKS (snappyHexMesh's MPI ranks, default 1),
# GEOMETRY_CACHE (where the hull geometry from openfoam-examples is kept, default WORK/openfoam-examples).
# Usage: cached-hull-case.sh small|400k|1M WORK
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
size=${1:?small, 400k or 1M}
work=${2:?the work folder}
case=$work/case-$size
# the template's files, of the mesh sizes this size's only (a new size does not rebuild the others)
stamp=$( (cd "$here" && find hullBox -type f ! -name 'meshSize.*' | sort | xargs cat && cat "hullBox/system/meshSize.$size") |
  md5sum | cut -d' ' -f1)
if [ ! -f "$case/case.foam" ] || [ "$(cat "$case/.template" 2>/dev/null)" != "$stamp" ]; then
  echo "Building the $size case in $case (snappyHexMesh on ${SNAPPY_RANKS:-1} rank(s); minutes for 1M)" >&2
  GEOMETRY_CACHE=${GEOMETRY_CACHE:-$work/openfoam-examples} bash "$here/make-hull-case.sh" "$size" "$case" "${SNAPPY_RANKS:-1}" >&2
  echo "$stamp" > "$case/.template"
else
  echo "Using the cached case $case ($(grep -E '^ *cells:' "$case/log.checkMesh" | tr -s ' '))" >&2
fi
echo "$case"
