#!/usr/bin/env bash
# Prints the folder that holds Debian's openfoam-examples (its usr/share/doc/openfoam-examples/
# examples/): / if the package is installed, else CACHE (default $1, or ./openfoam-examples),
# where the package is fetched with `apt-get download openfoam-examples` and unpacked with
# `dpkg-deb -x` the first time (it is not installed: container images often drop /usr/share/doc).
# Usage: root=$(openfoam-examples.sh [CACHE])
set -euo pipefail
relative=usr/share/doc/openfoam-examples/examples
if [ -d "/$relative/incompressible" ]; then echo /; exit 0; fi
cache=${1:-$PWD/openfoam-examples}
if [ ! -d "$cache/$relative/incompressible" ]; then
  echo "Fetching Debian's openfoam-examples (36 MB) into $cache" >&2
  mkdir -p "$cache"
  (cd "$cache" && { apt-get download openfoam-examples > apt-download.log 2>&1 || {
     # the package lists may be missing on a fresh machine
     sudo=""; [ "$(id -u)" -eq 0 ] || sudo=sudo
     $sudo apt-get update -q > /dev/null && apt-get download openfoam-examples > apt-download.log 2>&1; } ||
     { cat apt-download.log >&2; exit 1; } })
  debs=("$cache"/openfoam-examples_*.deb)
  dpkg-deb -x "${debs[0]}" "$cache"
  rm -f "$cache"/openfoam-examples_*.deb
fi
cd "$cache" && pwd
