#!/usr/bin/env bash
# The main job of the README: installs only what the program needs, builds only the command-line
# remesher, and runs it on its embedded default, CGAL's meshes/fandisk.off, writing results to
# ./out/. (scripts/test.sh builds and runs everything.)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install_dependencies.sh" --minimal
build="${POISSON_REMESH_BUILD_DIR:-$root/build}"
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
  -DPOISSON_REMESH_BUILD_EXAMPLES=ON -DPOISSON_REMESH_BUILD_TESTS=OFF -DPOISSON_REMESH_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" --target poisson_remesh -j "${POISSON_REMESH_JOBS:-$(nproc)}"
mkdir -p "$root/out"
# Our remesher at the input's vertex count, with the peer (CGAL isotropic_remeshing) beside it.
"$build/examples/Poisson_remesh/poisson_remesh" --compare-peer \
  --report "$root/out/fandisk_remeshed.json" --svg "$root/out/fandisk_remeshed_angles.svg" \
  "$build/data/meshes/fandisk.off" "$root/out/fandisk_remeshed.off"
