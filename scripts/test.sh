#!/usr/bin/env bash
# The test command of the README (and of CI): installs what is missing, builds the library's
# examples and tests (not the benchmark programs: benchmark/run_all.sh builds those), runs the whole
# suite with ctest, as many tests at once as there are cores (POISSON_REMESH_JOBS).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh" -DPOISSON_REMESH_BUILD_BENCHMARKS="${POISSON_REMESH_TEST_BENCHMARKS:-OFF}"
cd "${POISSON_REMESH_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j "${POISSON_REMESH_JOBS:-$(nproc)}" "$@"
