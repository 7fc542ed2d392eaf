#!/usr/bin/env bash
# Configures and builds Poisson_remesh (Release) in ./build, after installing what is missing.
# Usage: scripts/build.sh [extra cmake -D options...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install_dependencies.sh"
build="${POISSON_REMESH_BUILD_DIR:-$root/build}"
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
# (paths relative to the checkout in ccache's keys: a clone in another folder -- CI's -- reuses
# the objects of an earlier build of the same sources)
export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1
# (everything on: the quick start may have configured the same folder with less)
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
  -DPOISSON_REMESH_BUILD_EXAMPLES=ON -DPOISSON_REMESH_BUILD_TESTS=ON -DPOISSON_REMESH_BUILD_BENCHMARKS=ON "$@" >/dev/null
jobs="${POISSON_REMESH_JOBS:-$(nproc)}"
cmake --build "$build" -j "$jobs"
