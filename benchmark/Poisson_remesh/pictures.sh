#!/usr/bin/env bash
# pictures.sh BUILD_DIR [OUT_DIR] -- the pictures of RESULTS.md and the README: for fandisk,
# triceratops, cheese and head (open: one border), at the input's vertex count and seed 1,
# the input, our remesh and CGAL's isotropic_remeshing (10 iterations, calibrated to the same
# count) side by side, flat-shaded with their edges, the triangles under 30 degrees in red
# (poisson_remesh --compare-peer --picture, drawn by IO/write_mesh_svg.h), and the three angle
# histograms (--svg). The SVGs are turned into PNGs (rsvg-convert from Debian's librsvg2-bin,
# installed when missing and apt-get is at hand) at 1200 pixels wide; the PNGs and the histograms
# are the committed copies (the mesh SVGs are several megabytes each).
set -euo pipefail
build=$(cd "$1" && pwd)
out=${2:-$(dirname "$0")/pictures}
mkdir -p "$out"
bin=$build/examples/Poisson_remesh/poisson_remesh
data=$build/data/meshes
if ! command -v rsvg-convert > /dev/null && command -v apt-get > /dev/null; then
  sudo_cmd=; [ "$(id -u)" = 0 ] || sudo_cmd=sudo
  $sudo_cmd apt-get install -y -qq librsvg2-bin > /dev/null || true
fi
for m in fandisk triceratops cheese head; do
  "$bin" "$data/$m.off" "$out/$m.remeshed.off" --seed 1 --compare-peer --quiet \
    --picture "$out/$m.svg" --svg "$out/${m}_angles.svg" > "$out/$m.txt"
  rm -f "$out/$m.remeshed.off"
  if command -v rsvg-convert > /dev/null; then
    rsvg-convert -w 1200 -b white "$out/$m.svg" -o "$out/$m.png"
  else
    echo "pictures.sh: no rsvg-convert: $out/$m.svg left as SVG only" >&2
  fi
  echo "$m: $(grep -c '<path ' "$out/$m.svg") faces drawn, $(grep -c 'class="marked"' "$out/$m.svg") under 30 degrees"
done
