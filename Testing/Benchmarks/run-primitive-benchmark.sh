#!/usr/bin/env bash
# Primitive detection against CGAL's Efficient RANSAC (paper section 6.3): installs CGAL
# (libcgal-dev, for this benchmark only) if missing, sets up and builds (Testing/setup.sh), then
# prints one JSON line per mesh: CGAL's mechanical parts of Debian's libcgal-demo (fandisk,
# joint, anchor, couplingdown, pinion, part, pipe, rotor, mech-holes-shark), a generated part of
# about 100k faces, clean and noisy; median time and coverage over the runs given (default 15:
# coverage varies with the seed by a few faces on fandisk, where both are within 0.1 points),
# and the least coverage of any run.
# Usage: run-primitive-benchmark.sh [RUNS]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${MLSDEFORM_BUILD:-$root/build}
if ! dpkg-query -W -f='${Status}' libcgal-dev 2>/dev/null | grep -q "install ok installed"; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update -q
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends libcgal-dev
fi
bash "$root/Testing/setup.sh"
cmake "$build" -DMLSDEFORM_BENCHMARK_CGAL=ON > /dev/null
cmake --build "$build" --target BenchmarkPrimitiveDetection -j "$(nproc)"
"$build/Testing/Benchmarks/BenchmarkPrimitiveDetection" "$build/data" "${1:-15}" \
  fandisk joint anchor couplingdown pinion part pipe rotor mech-holes-shark
