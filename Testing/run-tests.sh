#!/usr/bin/env bash
# The whole test suite: sets up and builds if needed (Testing/setup.sh), runs ctest, then the C++
# tests again built with AddressSanitizer + UndefinedBehaviorSanitizer (run-sanitizer-tests.sh).
# A test whose program or data is missing reports "skipped" (CMake's mlsdeform_add_test): here,
# after the set-up has installed them, a missing one or a skipped test fails the run, so that CI
# cannot pass with tests that did not run.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${MLSDEFORM_BUILD:-$root/build}
bash "$root/Testing/setup.sh"

# What setup.sh installs for the tests: the programs they run, OpenFOAM's tools as they run them
# (in the environment of /usr/share/openfoam/etc/bashrc, as Examples/OpenFOAM/make-case.sh and
# the OpenFOAM tests do), the Python modules of Debian's Python (ParaView's), CGAL's demo meshes
# (the archive and the extracted files of the configured build).
missing=()
for program in pvpython pvbatch pvserver paraview mpiexec Xvfb xdpyinfo gmsh snappyHexMesh cgnscheck cgnsdiff aflr3_to_cgns ncdump; do
  command -v "$program" > /dev/null || missing+=("program $program")
done
for program in blockMesh snappyHexMesh checkMesh decomposePar adjointOptimisationFoam foamDictionary; do
  bash -c "source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1; command -v $program" > /dev/null ||
    missing+=("OpenFOAM's $program (after sourcing /usr/share/openfoam/etc/bashrc)")
done
/usr/bin/python3 -c "import numpy, matplotlib, PyQt5.QtWidgets" 2> /dev/null || missing+=("Python modules numpy, matplotlib, PyQt5")
cgal_data=$(sed -n 's/^MLSDEFORM_CGAL_DATA:FILEPATH=//p' "$build/CMakeCache.txt")
for file in /usr/share/openfoam/etc/bashrc "$cgal_data" "$build/data/fandisk.off" "$build/data/joint.off"; do
  [ -s "$file" ] || missing+=("file ${file:-MLSDEFORM_CGAL_DATA (not in $build/CMakeCache.txt)}")
done
examples=$(sed -n 's/^MLSDEFORM_OPENFOAM_EXAMPLES:PATH=//p' "$build/CMakeCache.txt")
[ -d "$examples/usr/share/doc/openfoam-examples/examples/incompressible/adjointOptimisationFoam" ] ||
  missing+=("OpenFOAM's adjoint tutorials (openfoam-examples) in ${examples:-MLSDEFORM_OPENFOAM_EXAMPLES (not in $build/CMakeCache.txt)}")
if ((${#missing[@]})); then
  printf 'run-tests.sh: missing after the set-up (Testing/setup.sh), the tests that need it would be skipped:\n' >&2
  printf '  %s\n' "${missing[@]}" >&2
  exit 1
fi

# ctest's output as before (CI reads its summary line), kept to find skipped tests in.
log="$build/Testing/run-tests.log"
(cd "$build" && ctest --output-on-failure -j "$(nproc)") | tee "$log"
if grep -q "(Skipped)\|(Disabled)\|(Not Run)" "$log"; then
  echo "run-tests.sh: tests did not run (listed above): the suite must run every test" >&2
  exit 1
fi
bash "$root/Testing/run-sanitizer-tests.sh"
