#!/usr/bin/env bash
# The test command of the README (and of CI): installs what is missing, builds, runs the whole suite with ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh"
cd "${POISSON_REMESH_BUILD_DIR:-$root/build}"
ctest --output-on-failure "$@"
