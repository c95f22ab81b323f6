#!/usr/bin/env bash
# Builds the sphere-in-a-wind-tunnel snappyHexMesh case (sphereChannel/: 19,697 points, 15,460
# cells graded from 0.5 in the far field to 0.03 at the sphere, 3 boundary layers on it) into the
# folder $1 with Debian's OpenFOAM: blockMesh, snappyHexMesh, checkMesh. About 3 s. With a second
# argument "decompose", decomposePar then splits it into 4 processor folders (system/decomposeParDict).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
target=${1:?usage: make-case.sh TARGET_FOLDER [decompose]}
rm -rf "$target"
mkdir -p "$(dirname "$target")"
cp -r "$here/sphereChannel" "$target"
cd "$target"
set +u
source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1 # (its foamEtcFile notes are noise)
set -u
blockMesh > log.blockMesh 2>&1 || { tail -20 log.blockMesh; exit 1; }
snappyHexMesh -overwrite > log.snappyHexMesh 2>&1 || { tail -20 log.snappyHexMesh; exit 1; }
checkMesh > log.checkMesh 2>&1 || { tail -20 log.checkMesh; exit 1; }
if [ "${2:-}" = decompose ]; then
  decomposePar > log.decomposePar 2>&1 || { tail -20 log.decomposePar; exit 1; }
fi
touch case.foam
echo "$target/case.foam: $(grep -E '^ *points:' log.checkMesh | tr -s ' ') $(grep -E '^ *cells:' log.checkMesh | tr -s ' ')"
