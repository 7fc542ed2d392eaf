#!/usr/bin/env bash
# profile_sampler.sh POISSON_SAMPLE MESH [VERTICES] -- where the sampler's time goes, per sample:
# poisson_sample is run once under `perf record` (call graphs by DWARF unwinding) and the share of
# the samples spent inside the geodesic propagation, the iso-curve extraction (with its chaining)
# and the boundary update is turned into microseconds per sample with the program's own timing
# (the fastest of three runs without perf, whose sampling slows the program down).
# Needs perf (Debian package linux-perf). The shares include the functions each stage calls.
set -euo pipefail
bin=$1 mesh=$2
vertices=${3:-$(awk '!/^#/ && NF { n++; if(n == 2) { print $1; exit } }' "$mesh")}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
perf record -q --call-graph dwarf,16384 -F 4000 -o "$tmp/perf.data" "$bin" "$mesh" "$tmp/s.xyz" --vertices "$vertices" 2> "$tmp/err" > /dev/null
line=$(grep "samples (" "$tmp/err")
samples=$(echo "$line" | sed -E 's/.*: ([0-9]+) samples.*/\1/')
seconds=
for run in 1 2 3; do
  s=$("$bin" "$mesh" "$tmp/s.xyz" --vertices "$vertices" 2>&1 > /dev/null | grep "samples (" | sed -E 's/.*, ([0-9.e-]+) s$/\1/')
  if [ -z "$seconds" ] || [ "$(echo "$s < $seconds" | bc -l)" = 1 ]; then seconds=$s; fi
done
perf report -i "$tmp/perf.data" --children -g none --stdio 2> /dev/null > "$tmp/report"
share() { grep -m1 -F "$1" "$tmp/report" | awk '{ sub("%", "", $1); print $1 }'; }
total=$(share "internal::poisson_disk_sample<")
printf '| %s | %s | %.3f | %.1f' "$(basename "$mesh" .off)" "$samples" "$seconds" "$(echo "$seconds * 1000000 / $samples" | bc -l)"
for stage in "::propagate_impl<" "::extract_iso_arcs<" "::chain_arcs_by_endpoints<" "::update<"; do
  s=$(share "$stage"); s=${s:-0}
  printf ' | %.1f' "$(echo "$seconds * 1000000 / $samples * $s / $total" | bc -l)"
done
printf ' |\n'
