#!/usr/bin/env bash
# Builds the benchmark case "DTC hull in a box" (hullBox/) into TARGET with Debian's OpenFOAM:
# surfaceFeatureExtract, blockMesh, snappyHexMesh (on RANKS MPI ranks: decomposePar, mpirun,
# reconstructParMesh; 1 = serial), checkMesh. The hull geometry (DTC-scaled.stl.gz) comes from
# Debian's package openfoam-examples: from /usr/share/doc/openfoam-examples if it is installed,
# else from $GEOMETRY_CACHE (default: next to TARGET), where the package is fetched with
# `apt-get download openfoam-examples` and unpacked with `dpkg-deb -x` (it is not installed).
# Usage: make-hull-case.sh small|400k|1M TARGET [RANKS]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
size=${1:?usage: make-hull-case.sh small|400k|1M TARGET [RANKS]}
target=${2:?usage: make-hull-case.sh small|400k|1M TARGET [RANKS]}
ranks=${3:-1}
[ -f "$here/hullBox/system/meshSize.$size" ] || { echo "unknown size '$size' (small, 400k or 1M)" >&2; exit 2; }
mkdir -p "$(dirname "$target")"
target=$(cd "$(dirname "$target")" && pwd)/$(basename "$target")

# The hull surface.
examples=$("$here/../../../Examples/OpenFOAM/openfoam-examples.sh" "${GEOMETRY_CACHE:-$(dirname "$target")/openfoam-examples}")
stl=$examples/usr/share/doc/openfoam-examples/examples/resources/geometry/DTC-scaled.stl.gz

rm -rf "$target"
cp -r "$here/hullBox" "$target"
cd "$target"
cp "system/meshSize.$size" system/meshSize
mkdir -p constant/triSurface
gzip -dc "$stl" > constant/triSurface/hull.stl
set +u
source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1
set -u
run() { # run LOG COMMAND...: the command's output in LOG, its wall time added to log.times
  local log=$1 start=$SECONDS
  shift
  "$@" > "$log" 2>&1 || { echo "$* failed:"; tail -30 "$log"; exit 1; }
  echo "$log $((SECONDS - start)) s" >> log.times
}
run log.surfaceFeatureExtract surfaceFeatureExtract
run log.blockMesh blockMesh
if [ "$ranks" -gt 1 ]; then
  foamDictionary -entry numberOfSubdomains -set "$ranks" system/decomposeParDict > /dev/null
  foamDictionary -entry coeffs/n -set "($ranks 1 1)" system/decomposeParDict > /dev/null
  run log.decomposePar decomposePar -force
  run log.snappyHexMesh mpirun --allow-run-as-root --oversubscribe -np "$ranks" snappyHexMesh -parallel -overwrite
  run log.reconstructParMesh reconstructParMesh -constant -mergeTol 1e-6
  rm -rf processor*
else
  run log.snappyHexMesh snappyHexMesh -overwrite
fi
# snappyHexMesh leaves cellLevel, pointLevel etc. in polyMesh; moveMesh and the reader do not need them
run log.checkMesh checkMesh -constant
touch case.foam
echo "$target: $(grep -E '^ *points:' log.checkMesh | tr -s ' ')$(grep -E '^ *cells:' log.checkMesh | tr -s ' '); $(paste -sd, log.times)"
