#!/usr/bin/env bash
# Builds the NACA 0012 laminar drag case of OpenFOAM's adjoint tutorials (adjointOptimisationFoam
# sensitivityMaps/naca0012/laminar/drag: 37,800 cells, 76,806 points, 2D with front and back
# planes in one `empty` patch, Re 1000 at 2 degrees) into TARGET, from Debian's openfoam-examples
# (fetched by openfoam-examples.sh into CACHE if it is not installed). The surface sensitivity is
# asked for as dJ/dx: `includeSurfaceArea true` (the solver's default divides each point's value
# by its faces' area) and `writeAllSurfaceFiles true` (also the vector field pointSensVec<solver>ESI
# beside pointSensNormal<solver>ESI). Serial: the case is not decomposed.
# Usage: make-naca0012-case.sh TARGET [PRIMAL_ITERATIONS [ADJOINT_ITERATIONS [CACHE]]]
#   (the tutorial's 3000 and 3000 by default; each stops earlier at residuals 1e-7)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
usage="usage: make-naca0012-case.sh TARGET [PRIMAL_ITERATIONS [ADJOINT_ITERATIONS [CACHE]]]"
target=${1:?$usage}
primal=${2:-3000}
adjoint=${3:-3000}
mkdir -p "$(dirname "$target")"
target=$(cd "$(dirname "$target")" && pwd)/$(basename "$target")
examples=$("$here/openfoam-examples.sh" "${4:-$(dirname "$target")/openfoam-examples}")
tutorials=$examples/usr/share/doc/openfoam-examples/examples/incompressible/adjointOptimisationFoam

rm -rf "$target"
cp -r "$tutorials/sensitivityMaps/naca0012/laminar/drag" "$target"
cp -r "$tutorials/resources/meshes/naca0012/polyMesh" "$target/constant/"
find "$target" -name '*.gz' -exec gunzip -f {} +
rm -f "$target/Allrun" "$target/Allclean" "$target/system/decomposeParDict"
cd "$target"
set +u
source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1
set -u
dict=system/optimisationDict
foamDictionary -entry optimisation.sensitivities.includeSurfaceArea -add true $dict > /dev/null
foamDictionary -entry optimisation.sensitivities.writeAllSurfaceFiles -add true $dict > /dev/null
foamDictionary -entry primalSolvers.op1.solutionControls.nIters -set "$primal" $dict > /dev/null
foamDictionary -entry adjointManagers.adjManager1.adjointSolvers.adjS1.solutionControls.nIters -set "$adjoint" $dict > /dev/null
# one time step per iteration: the primal's, then the adjoint's
foamDictionary -entry endTime -set $((primal + adjoint)) system/controlDict > /dev/null
foamDictionary -entry writeInterval -set $((primal + adjoint)) system/controlDict > /dev/null
touch case.foam
echo "$target/case.foam: NACA 0012 laminar drag, $primal primal and $adjoint adjoint iterations"
