#!/usr/bin/env bash
# Runs every test: installs missing Debian packages, builds into build/, runs ctest.
# Exits non-zero on any failure. Extra arguments go to ctest (e.g. -L unit, -R lpv).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/scripts/deps.sh"
cavelight_install_deps
cavelight_build "$root"
cd "$root/build"
ctest --output-on-failure -j "$(nproc)" "$@"
