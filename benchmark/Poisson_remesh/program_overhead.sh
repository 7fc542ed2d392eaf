#!/usr/bin/env bash
# The command-line program's wall time against the remesh inside it (issue 25: reading, the
# before/after report and writing should add at most 30%), on CGAL's data meshes.
# Usage: program_overhead.sh [BUILD_DIR] [MESH...]   (default: every mesh of CGAL's data set
# with 500-40,000 vertices; a mesh is a name of build/data/meshes without .off)
# Prints one Markdown row per mesh: vertices, remesh seconds, program wall seconds, their ratio.
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${1:-$root/build}"; shift || true
program="$build/examples/Poisson_remesh/poisson_remesh"
data="$build/data/meshes"
meshes=("$@")
if [ ${#meshes[@]} -eq 0 ]; then
  for f in "$data"/*.off; do
    n=$(awk 'NR==1 && $1 ~ /^OFF/ { if (NF > 1) { print $2; exit } next } NR<=3 && NF>=2 && $1 ~ /^[0-9]+$/ { print $1; exit }' "$f")
    [ -n "$n" ] && [ "$n" -ge 500 ] && [ "$n" -le 40000 ] && meshes+=("$(basename "$f" .off)")
  done
fi
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
echo "| mesh | input V | remesh (s) | program (s) | program / remesh |"
echo "|---|---:|---:|---:|---:|"
for m in "${meshes[@]}"; do
  # (bash's own clock: a `date` process for each reading added its start-up to the program's time)
  start=$EPOCHREALTIME
  "$program" --quiet "$data/$m.off" "$out/$m.off" > "$out/log" 2>&1
  code=$?
  end=$EPOCHREALTIME
  remesh=$(sed -n 's/.*vertices \.\.\. \([0-9.e-]*\) s (features.*/\1/p' "$out/log" | head -1)
  v=$(sed -n 's/.*(\([0-9]*\) vertices) to about.*/\1/p' "$out/log" | head -1)
  if [ "$code" -ne 0 ] || [ -z "$remesh" ]; then echo "| $m | ${v:-?} | failed (exit $code) | | |"; continue; fi
  awk -v m="$m" -v v="$v" -v r="$remesh" -v s="$start" -v e="$end" 'BEGIN { w = e - s; printf "| %s | %s | %.2f | %.2f | %.2f |\n", m, v, r, w, w / r }'
done
