#!/usr/bin/env bash
# Builds the sphere-in-a-channel snappyHexMesh case (sphereChannel/: 11k points, 3 boundary
# layers on the sphere) into the folder $1 with Debian's OpenFOAM: blockMesh, snappyHexMesh,
# checkMesh. About 2 s.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
target=${1:?usage: make-case.sh TARGET_FOLDER}
rm -rf "$target"
cp -r "$here/sphereChannel" "$target"
cd "$target"
set +u
source /usr/share/openfoam/etc/bashrc
set -u
blockMesh > log.blockMesh 2>&1 || { tail -20 log.blockMesh; exit 1; }
snappyHexMesh -overwrite > log.snappyHexMesh 2>&1 || { tail -20 log.snappyHexMesh; exit 1; }
checkMesh > log.checkMesh 2>&1 || { tail -20 log.checkMesh; exit 1; }
touch case.foam
echo "$target/case.foam: $(grep -E '^ *points:' log.checkMesh | tr -s ' ') $(grep -E '^ *cells:' log.checkMesh | tr -s ' ')"
