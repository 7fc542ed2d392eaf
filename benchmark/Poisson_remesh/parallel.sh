#!/usr/bin/env bash
# The parallel mode (issue 26): the remesh time with 1 thread and with N threads (default 2), and
# CGAL's isotropic_remeshing (10 iterations, the peer) at the same vertex count, all three run by
# the command-line program in this script, one after the other; and whether the outputs of 1 and
# N threads are the same file.
# Usage: parallel.sh [BUILD_DIR] [THREADS] [MESH...]   (default: armadillo bunny00 camel fandisk
# elephant; a mesh is a name of build/data/meshes without .off). Each time is the best of 2 runs
# of the remesh call inside the program (the figure it prints), seed 1.
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${1:-$root/build}"; shift || true
threads="${1:-2}"; shift || true
program="$build/examples/Poisson_remesh/poisson_remesh"
data="$build/data/meshes"
meshes=("$@")
[ ${#meshes[@]} -eq 0 ] && meshes=(armadillo bunny00 camel fandisk elephant)
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
seconds() { sed -n 's/.* \.\.\. \([0-9.e-]*\) s (.*/\1/p' "$1" | head -1; }
best() {   # best() NAME ARGS...: the smaller remesh time of two runs; the output kept in $out/NAME.off
  local name=$1; shift
  local b=""
  for run in 1 2; do
    "$program" --quiet --no-self-intersections --seed 1 "$@" "$out/$name.off" > "$out/$name.log" 2>&1 || { echo "failed"; return; }
    local s; s=$(seconds "$out/$name.log")
    if [ -z "$b" ] || awk -v s="$s" -v b="$b" 'BEGIN { exit !(s < b) }'; then b=$s; fi
  done
  echo "$b"
}
echo "| mesh | input V | ours, 1 thread (s) | ours, $threads threads (s) | speed-up | CGAL (s) | ours / CGAL, 1 thread | ours / CGAL, $threads threads | same output |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|:-:|"
for m in "${meshes[@]}"; do
  in="$data/$m.off"
  [ -f "$in" ] || { echo "| $m | missing | | | | | | | |"; continue; }
  one=$(best one --threads 1 "$in")
  many=$(best many --threads "$threads" "$in")
  peer=$(best peer --method isotropic --iterations 10 --threads 1 "$in")
  v=$(sed -n 's/.*(\([0-9]*\) vertices) to about.*/\1/p' "$out/one.log" | head -1)
  same=no; cmp -s "$out/one.off" "$out/many.off" && same=yes
  awk -v m="$m" -v v="$v" -v a="$one" -v b="$many" -v p="$peer" -v same="$same" \
    'BEGIN { printf "| %s | %s | %.2f | %.2f | %.2fx | %.2f | %.1fx | %.1fx | %s |\n", m, v, a, b, a / b, p, a / p, b / p, same }'
done
