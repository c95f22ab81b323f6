#!/usr/bin/env bash
# The whole test suite: sets up and builds if needed (Testing/setup.sh), runs ctest, then the C++
# tests again built with AddressSanitizer + UndefinedBehaviorSanitizer (run-sanitizer-tests.sh).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/Testing/setup.sh"
(cd "${MLSDEFORM_BUILD:-$root/build}" && ctest --output-on-failure -j "$(nproc)")
bash "$root/Testing/run-sanitizer-tests.sh"
