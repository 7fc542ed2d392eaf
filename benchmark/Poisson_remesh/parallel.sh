#!/usr/bin/env bash
# The parallel mode (issue 26): the remesh time of the parallel mode with 1 thread and with N
# threads (default 2; the same output, compared), and
# CGAL's isotropic_remeshing (10 iterations, the peer) at the same vertex count, all three run by
# the command-line program in this script, one after the other; and whether the outputs of 1 and
# N threads are the same file.
# Usage: parallel.sh [BUILD_DIR] [THREADS] [MESH...]   (default: armadillo bunny00 camel fandisk
# elephant; a mesh is a name of build/data/meshes without .off). Each time is the best of 2 runs
# (RUNS=N: of N) of the remesh call inside the program (the figure it prints), seed 1, the three
# alternated run by run; the speed-up also as the median of each run's own 1-thread / N-thread ratio.
# Then the sampler alone (poisson_sample): samples per second of the sequential sampler, and of
# the parallel mode's slabs with 1 and N threads.
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
runs="${RUNS:-2}"   # (RUNS=N: the best of N runs of each remesh; this machine's speed moves by up to 40%)
once() {   # once() NAME ARGS...: the remesh time of one run; the output kept in $out/NAME.off
  local name=$1; shift
  "$program" --quiet --no-self-intersections --seed 1 "$@" "$out/$name.off" > "$out/$name.log" 2>&1 || { echo "failed"; return; }
  seconds "$out/$name.log"
}
echo "| mesh | input V | ours, 1 thread (s) | ours, $threads threads (s) | speed-up | speed-up, median of the runs' | CGAL (s) | ours / CGAL, 1 thread | ours / CGAL, $threads threads | same output |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|:-:|"
for m in "${meshes[@]}"; do
  in="$data/$m.off"
  [ -f "$in" ] || { echo "| $m | missing | | | | | | | | |"; continue; }
  # (the three alternated run by run: this machine's speed drifts within minutes)
  times=""
  for run in $(seq "$runs"); do
    times="$times $(once one --threads 1 "$in") $(once many --threads "$threads" "$in") $(once peer --method isotropic --iterations 10 --threads 1 "$in")"
  done
  case "$times" in *failed*) echo "| $m | | failed | | | | | | | |"; continue ;; esac
  v=$(sed -n 's/.*(\([0-9]*\) vertices) to about.*/\1/p' "$out/one.log" | head -1)
  same=no; cmp -s "$out/one.off" "$out/many.off" && same=yes
  echo "$times" | awk -v m="$m" -v v="$v" -v same="$same" '{
    n = NF / 3
    for(i = 0; i < n; ++i) {
      o = $(3 * i + 1); t = $(3 * i + 2); p = $(3 * i + 3)
      if(i == 0 || o < a) a = o
      if(i == 0 || t < b) b = t
      if(i == 0 || p < c) c = p
      r[i] = o / t
    }
    for(i = 0; i < n; ++i) for(j = i + 1; j < n; ++j) if(r[j] < r[i]) { x = r[i]; r[i] = r[j]; r[j] = x }
    med = n % 2 ? r[(n - 1) / 2] : (r[n / 2 - 1] + r[n / 2]) / 2
    printf "| %s | %s | %.2f | %.2f | %.2fx | %.2fx | %.2f | %.1fx | %.1fx | %s |\n", m, v, a, b, a / b, med, c, a / c, b / c, same
  }'
done
echo
# the sampler alone: poisson_sample at the input's vertex count, sequential (the default) and in
# the parallel mode (slabs) with 1 and N threads; samples per second of the best of 2 runs
echo "| mesh | samples, sequential | samples / s, sequential | samples, parallel mode | samples / s, 1 thread | samples / s, $threads threads | same set for 1 and $threads threads |"
echo "|---|---:|---:|---:|---:|---:|:-:|"
sampler="$build/examples/Poisson_remesh/poisson_sample"
rate() {   # rate() NAME ARGS...: "samples rate" of the faster of two runs; the output kept in $out/NAME.xyz
  local name=$1; shift
  local best_rate=0 n=0
  for run in 1 2; do
    "$sampler" "$@" "$out/$name.xyz" --seed 1 > /dev/null 2> "$out/$name.log" || { echo "failed 0"; return; }
    n=$(sed -n 's/^poisson_sample: \([0-9]*\) samples.*/\1/p' "$out/$name.log")
    local s; s=$(sed -n 's/.*, \([0-9.e-]*\) s$/\1/p' "$out/$name.log")
    best_rate=$(awk -v n="$n" -v s="$s" -v b="$best_rate" 'BEGIN { r = n / s; print (r > b ? r : b) }')
  done
  echo "$n $best_rate"
}
for m in "${meshes[@]}"; do
  in="$data/$m.off"
  [ -f "$in" ] || continue
  v=$(grep -v '^#' "$in" | head -2 | awk 'NR == 1 && $1 != "OFF" { print $2; exit } NR == 2 { print $1 }')
  read -r ns rs <<< "$(rate seq "$in" --vertices "$v")"
  read -r n1 r1 <<< "$(rate one "$in" --vertices "$v" --threads 1)"
  read -r _ rn <<< "$(rate many "$in" --vertices "$v" --threads "$threads")"
  same=no; cmp -s "$out/one.xyz" "$out/many.xyz" && same=yes
  awk -v m="$m" -v ns="$ns" -v rs="$rs" -v n1="$n1" -v r1="$r1" -v rn="$rn" -v same="$same" \
    'BEGIN { printf "| %s | %d | %.0f | %d | %.0f | %.0f | %s |\n", m, ns, rs, n1, r1, rn, same }'
done
