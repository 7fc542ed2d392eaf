#!/usr/bin/env bash
# Builds the libFuzzer targets of test/Poisson_remesh/fuzz with clang (AddressSanitizer on) and
# runs each on a number of generated inputs. Usage: scripts/fuzz.sh [RUNS] [TARGET...]
#   RUNS     inputs per target (default 2000; the smoke run of the test suite uses 300)
#   TARGET   fuzz_read_surface_mesh, fuzz_poisson_remesh (default: both)
# A longer run: scripts/fuzz.sh 1000000 fuzz_read_surface_mesh, or run the binary in
# build/fuzz/ by hand with libFuzzer's options (-max_total_time=3600 -jobs=2 CORPUS_DIR ...).
# Exit status non-zero when a target crashes, hangs (over 20 s on one input) or leaks.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
runs="${1:-2000}"; shift || true
targets=("$@"); [ ${#targets[@]} -gt 0 ] || targets=(fuzz_read_surface_mesh fuzz_poisson_remesh)
out="${POISSON_REMESH_BUILD_DIR:-$root/build}/fuzz"; mkdir -p "$out"
cxx=(clang++); command -v ccache >/dev/null 2>&1 && cxx=(ccache clang++)
command -v clang++ >/dev/null 2>&1 || { echo "clang++ is missing: apt-get install clang" >&2; exit 1; }
# CGAL's own assertions are on (they check the library's preconditions on every input), except
# in the ctest smoke run (POISSON_REMESH_FUZZ_FRESH=1), which must stay within CI's time:
# POISSON_REMESH_FUZZ_ASSERTIONS=0 or 1 overrides
assertions=
if [ "${POISSON_REMESH_FUZZ_ASSERTIONS:-$([ "${POISSON_REMESH_FUZZ_FRESH:-0}" = 1 ] && echo 0 || echo 1)}" = 0 ]; then
  assertions=-DCGAL_NDEBUG
fi
# Eigen (the curvature density's jet fitting): pkg-config's path, else Debian's
eigen=$(pkg-config --cflags eigen3 2>/dev/null || echo "-I/usr/include/eigen3")
for t in "${targets[@]}"; do
  "${cxx[@]}" -std=c++17 -O1 -g -fsanitize=fuzzer,address $assertions -I"$root/include" $eigen \
    "$root/test/Poisson_remesh/fuzz/$t.cpp" -o "$out/$t" -lgmp -lmpfr
  # the corpus grows from run to run in build/fuzz; POISSON_REMESH_FUZZ_FRESH=1 (the ctest smoke
  # run) starts from an empty one, so that its cost does not grow with earlier long runs
  corpus="$out/$t.corpus"
  if [ "${POISSON_REMESH_FUZZ_FRESH:-0}" = 1 ]; then corpus=$(mktemp -d); fi
  mkdir -p "$corpus"
  (cd "$out" && "./$t" -runs="$runs" -timeout=20 -rss_limit_mb=4096 -seed=1 -print_final_stats=1 "$corpus" > "$t.log" 2>&1) || {
    echo "$t: FAILED after some of $runs inputs (log: $out/$t.log)"; tail -30 "$out/$t.log"; exit 1; }
  done_runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$out/$t.log" | grep -o '[0-9]*$' || echo "?")
  echo "$t: $done_runs inputs, no crash"
  if [ "${POISSON_REMESH_FUZZ_FRESH:-0}" = 1 ]; then rm -rf "$corpus"; fi
done
