#!/usr/bin/env bash
# The main job of the README: installs what is missing, builds, and runs the command-line
# remesher on its embedded default, CGAL's meshes/fandisk.off, writing results to ./out/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh"
build="${POISSON_REMESH_BUILD_DIR:-$root/build}"
mkdir -p "$root/out"
# Our remesher at the input's vertex count, with the peer (CGAL isotropic_remeshing) beside it.
"$build/examples/Poisson_remesh/poisson_remesh" --compare-peer \
  --report "$root/out/fandisk_remeshed.json" --svg "$root/out/fandisk_remeshed_angles.svg" \
  "$build/data/meshes/fandisk.off" "$root/out/fandisk_remeshed.off"
