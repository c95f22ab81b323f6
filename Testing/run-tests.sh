#!/usr/bin/env bash
# The whole test suite: sets up and builds if needed (Testing/setup.sh), then runs ctest.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/Testing/setup.sh"
cd "${MLSDEFORM_BUILD:-$root/build}"
ctest --output-on-failure -j "$(nproc)"
