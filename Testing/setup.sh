#!/usr/bin/env bash
# Sets up a Debian 12 machine for MLSDeform and builds it: installs the Debian packages that are
# missing (ParaView 5.11 with its development files and everything its CMake package needs,
# Qt's OpenGL module for the plugin's GUI part, Eigen, CHOLMOD with OpenBLAS, CGAL's demo meshes, Xvfb and PyQt5 for the GUI tests, and for the paper comparisons gmsh
# and matplotlib, scipy for the optimization example, OpenFOAM for the CFD round-trip tests and examples, and OpenFOAM's tutorials from
# openfoam-examples, unpacked into the build, for the adjoint tests, CalculiX for the structural loop's tests and example and meshio for its benchmark, the CGNS project's
# tools (cgns-convert: cgnscheck, cgnsdiff, CGNS 3.4) and ncdump (netcdf-bin) to check variants; CGNS files go
# through ParaView's own CGNS library, Exodus files through netCDF), then configures and builds into build/ (or
# $MLSDEFORM_BUILD). Running it again only rebuilds what changed.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${MLSDEFORM_BUILD:-$root/build}

packages=(
  cmake g++ make
  paraview paraview-dev python3-paraview python3-numpy
  qtbase5-dev qttools5-dev libqt5svg5-dev qtxmlpatterns5-dev-tools libutfcpp-dev
  libqt5opengl5-dev
  libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libnetcdf-dev libgdal-dev libboost-dev
  libdouble-conversion-dev liblz4-dev liblzma-dev libexpat1-dev libfreetype-dev
  libglew-dev libgl2ps-dev libjpeg-dev libpng-dev libtiff-dev libtheora-dev
  libxml2-dev libx11-dev zlib1g-dev python3-dev
  libeigen3-dev libsuitesparse-dev libblas-dev libopenblas0-openmp
  libcgal-demo xvfb xauth x11-utils
  gmsh python3-matplotlib python3-pyqt5 python3-scipy time
  openfoam calculix-ccx python3-meshio cgns-convert netcdf-bin
)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]})); then
  echo "Installing ${#missing[@]} Debian packages: ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update -q
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

mkdir -p "$build"
# OpenFOAM's adjoint tutorials (the NACA 0012 case of the adjoint tests and examples): Debian's
# openfoam-examples, unpacked into the build (its 36 MB are fetched once)
"$root/Examples/OpenFOAM/openfoam-examples.sh" "$build/data/openfoam-examples" > /dev/null
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release > "$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" -j "$(nproc)"
echo "Built; the plugin is $build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so"
