#!/usr/bin/env bash
# The structural benchmarks' plate deck (Examples/Structural/plate.py, two holes, C3D10) of the given
# size, meshed by Gmsh once and cached in BUILD/deck-benchmark/plate-SIZE (small: mesh size 0.3,
# seconds; 300k: mesh size 0.093; 1M: mesh size 0.062, about 1M nodes, a few minutes). Prints the
# deck's path; what it does goes to stderr. Usage: cached-plate.sh small|300k|1M BUILD
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
size=${1:?small or 1M}
build=${2:?the build folder}
case "$size" in
  small) mesh_size=0.3 ;;
  300k) mesh_size=0.093 ;;
  1M) mesh_size=0.062 ;;
  *) echo "--nodes small, 300k or 1M, not $size" >&2; exit 2 ;;
esac
folder=$build/deck-benchmark/plate-$size
if [ ! -f "$folder/plate.inp" ]; then
  echo "Meshing the plate (mesh size $mesh_size) into $folder ..." >&2
  rm -rf "$folder.partial"
  PYTHONPATH="$root/Examples/Structural" /usr/bin/python3 -c "
import plate, sys
plate.mesh_plate(sys.argv[1], holes=((3.0, 2.0, 0.8), (7.0, 2.0, 0.8)), size=float(sys.argv[2]))
plate.write_analysis(sys.argv[1])" "$folder.partial" "$mesh_size" >&2
  mv "$folder.partial" "$folder"
fi
echo "$folder/plate.inp"
