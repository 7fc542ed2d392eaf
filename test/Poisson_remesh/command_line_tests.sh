#!/usr/bin/env bash
# Drives the command-line programs as a user would and checks exit codes, messages and that an
# output file is never left partial or clobbered. Usage: command_line_tests.sh MESH_QUALITY POISSON_REMESH DATA_DIR
set -u
mesh_quality="$1"; poisson_remesh="$2"; data="$3"; poisson_sample="$4"; geodesic_distances="$5"
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
passed=0; failed=0
check() { # check NAME CONDITION...
  local name="$1"; shift
  if "$@"; then passed=$((passed+1)); else failed=$((failed+1)); echo "FAILED: $name"; fi
}
run() { # run EXPECTED_CODE CMD... ; leaves stdout in $dir/out, stderr in $dir/err
  local expected="$1"; shift
  "$@" >"$dir/out" 2>"$dir/err"; local code=$?
  [ "$code" -eq "$expected" ] || { echo "exit $code, expected $expected: $*"; cat "$dir/err"; return 1; }
}
has() { grep -q -- "$2" "$dir/$1" || { echo "'$2' not in $1:"; cat "$dir/$1"; return 1; }; }

# mesh_quality
check "mesh_quality --help" run 0 "$mesh_quality" --help
check "help text" has out "usage: mesh_quality"
check "mesh_quality on triceratops" run 0 "$mesh_quality" "$data/meshes/triceratops.off"
check "table has the vertex count" has out "vertices *2832"
check "table has the mean min angle" has out "mean min angle (deg) *29.83"
check "mesh_quality --json with reference" run 0 "$mesh_quality" --json --svg "$dir/h.svg" "$data/meshes/fandisk.off" "$data/meshes/fandisk.off"
check "json has hausdorff 0" has out '"hausdorff_over_diagonal": 0'
check "svg written" test -s "$dir/h.svg"
check "missing file" run 1 "$mesh_quality" "$dir/none.off"
check "missing file message" has err "no such file"
printf 'OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n' > "$dir/nan.off"
check "nan input" run 1 "$mesh_quality" "$dir/nan.off"
check "nan message" has err "NaN or infinite coordinate at line 4"
check "unknown option" run 2 "$mesh_quality" --bogus "$data/meshes/fandisk.off"
check "no argument" run 2 "$mesh_quality"

# poisson_remesh
check "poisson_remesh --help" run 0 "$poisson_remesh" --help
check "help lists --vertices" has out "--vertices N"
echo precious > "$dir/keep.off"
check "unknown method" run 2 "$poisson_remesh" --method magic "$data/meshes/fandisk.off" "$dir/keep.off"
check "output untouched (method)" grep -q precious "$dir/keep.off"
check "poisson remesh with the peer beside" run 0 "$poisson_remesh" --vertices 1200 --seed 2 --compare-peer --picture "$dir/pic.svg" "$data/meshes/elephant.off" "$dir/ours.off"
check "table has ours and the peer" sh -c "grep -q 'output (Poisson)' '$dir/out' && grep -q 'peer (CGAL isotropic)' '$dir/out'"
check "poisson output written" sh -c "head -1 '$dir/ours.off' | grep -q OFF"
check "picture: three panels" sh -c "grep -q '>input (' '$dir/pic.svg' && grep -q '>output (Poisson) (' '$dir/pic.svg' && grep -q '>peer (CGAL isotropic) (' '$dir/pic.svg'"
# one path per face: the input's and ours (faces in the OFF headers) and the peer's (at least one)
faces_of() { awk '!/^#/ && NF { n++; if(n == 2) { print $2; exit } }' "$1"; }
check "picture: a path per face" sh -c "test \$(grep -c '<path ' '$dir/pic.svg') -gt \$(( $(faces_of "$data/meshes/elephant.off") + $(faces_of "$dir/ours.off") ))"
check "picture refused in a batch" run 2 "$poisson_remesh" --picture "$dir/p.svg" -o "$dir/batch_pic" "$data/meshes/elephant.off"
check "same seed, same output" sh -c "'$poisson_remesh' --vertices 1200 --seed 2 '$data/meshes/elephant.off' '$dir/ours2.off' >/dev/null && cmp -s '$dir/ours.off' '$dir/ours2.off'"
# the parallel mode's threads do not change the output (the run above used all cores)
check "one thread, same output" sh -c "'$poisson_remesh' --vertices 1200 --seed 2 --threads 1 '$data/meshes/elephant.off' '$dir/ours3.off' >/dev/null && cmp -s '$dir/ours.off' '$dir/ours3.off'"
check "no threads" run 2 "$poisson_remesh" --threads 0 "$data/meshes/elephant.off" "$dir/keep.off"
check "names the rule" has err "--threads needs at least 1"
# poisson_sample's parallel mode (slabs): one set for any number of threads, another than the
# sequential sampler's
check "sampler, 1 thread" run 0 "$poisson_sample" "$data/meshes/camel.off" "$dir/s1.xyz" --vertices 3000 --seed 3 --threads 1
check "sampler, 2 threads, same set" sh -c "'$poisson_sample' '$data/meshes/camel.off' '$dir/s2.xyz' --vertices 3000 --seed 3 --threads 2 2>/dev/null && cmp -s '$dir/s1.xyz' '$dir/s2.xyz'"
check "sampler, sequential, another set" sh -c "'$poisson_sample' '$data/meshes/camel.off' '$dir/s0.xyz' --vertices 3000 --seed 3 2>/dev/null && ! cmp -s '$dir/s1.xyz' '$dir/s0.xyz'"
check "sampler, no threads" run 2 "$poisson_sample" "$data/meshes/camel.off" "$dir/s3.xyz" --vertices 3000 --threads 0
# pointed tips sampled finer (feature grading), or not with --no-grading
check "horn tips graded" run 0 "$poisson_remesh" --vertices 1500 --no-self-intersections "$data/meshes/triceratops.off" "$dir/graded.off"
check "graded tips reported" has out "pointed tip(s)"
check "no grading" run 0 "$poisson_remesh" --vertices 1500 --no-self-intersections --no-grading "$data/meshes/triceratops.off" "$dir/graded.off"
check "no graded tips reported" sh -c "! grep -q 'pointed tip' '$dir/out'"
# remade finer where the first remesh cut itself or kept triangles under 30 degrees (elephant at
# 1000 vertices, seed 2: once), or not with --regrading 0
check "remade once" run 0 "$poisson_remesh" --vertices 1000 --seed 2 --no-self-intersections "$data/meshes/elephant.off" "$dir/remade.off"
check "remake reported" has out "remeshed 1 more time"
check "no remakes" run 0 "$poisson_remesh" --vertices 1000 --seed 2 --no-self-intersections --regrading 0 "$data/meshes/elephant.off" "$dir/remade.off"
check "no remake reported" sh -c "! grep -q 'remeshed' '$dir/out'"
check "bad remake count" run 2 "$poisson_remesh" --regrading many "$data/meshes/elephant.off" "$dir/keep.off"
# the regions at fault alone remade (femur at its own count, seed 1: triangles under 30 degrees)
check "local remakes" run 0 "$poisson_remesh" --vertices 3897 --seed 1 --local-remakes "$data/meshes/femur.off" "$dir/local.off"
check "local remake reported" has out "remeshed the regions at fault"
# adaptive density (issue 6)
check "adaptive remesh" run 0 "$poisson_remesh" --adaptive --vertices 1500 --no-self-intersections --density-svg "$dir/d.svg" "$data/meshes/elephant.off" "$dir/adaptive.off"
check "adaptive spacing range printed" has out "(median; from"
check "density map written" grep -q "</svg>" "$dir/d.svg"
check "adaptive output written" sh -c "head -1 '$dir/adaptive.off' | grep -q OFF"
check "tuning needs --adaptive" run 2 "$poisson_remesh" --gamma 2 "$data/meshes/fandisk.off" "$dir/keep.off"
check "names the rule" has err "go with --adaptive"
check "min edge above max edge" run 2 "$poisson_remesh" --adaptive --min-edge 0.2 --max-edge 0.1 "$data/meshes/fandisk.off" "$dir/keep.off"
check "output untouched (adaptive usage)" grep -q precious "$dir/keep.off"
printf '1\n2\n3\n' > "$dir/short.txt"
check "density file of the wrong length" run 1 "$poisson_remesh" --density "$dir/short.txt" "$data/meshes/triceratops.off" "$dir/keep.off"
check "names the counts" has err "has 3 values for 2832 vertices"
check "output untouched (density file)" grep -q precious "$dir/keep.off"
awk 'NR>2 && NF==3 { print 1 + ($1 > 0 ? 3 : 0) }' "$data/meshes/elephant.off" | head -2775 > "$dir/user.txt"
check "user density remesh" run 0 "$poisson_remesh" --density "$dir/user.txt" --vertices 1000 --no-self-intersections "$data/meshes/elephant.off" "$dir/user.off"
printf '1\n-2\n' > "$dir/neg.txt"
check "negative density" run 1 "$poisson_remesh" --density "$dir/neg.txt" "$data/meshes/triceratops.off" "$dir/keep.off"
check "names the line" has err "line 2"
check "bad number" run 2 "$poisson_remesh" --vertices abc --method isotropic "$data/meshes/fandisk.off" "$dir/keep.off"
check "bad input keeps output" run 1 "$poisson_remesh" --method isotropic "$dir/nan.off" "$dir/keep.off"
check "output untouched (input)" grep -q precious "$dir/keep.off"
check "unwritable output" run 3 "$poisson_remesh" --method isotropic --vertices 300 --no-self-intersections "$data/meshes/triceratops.off" "$dir/no/such/out.off"
check "peer remesh" run 0 "$poisson_remesh" --method isotropic --vertices 1500 --report "$dir/r.json" --svg "$dir/r.svg" "$data/meshes/triceratops.off" "$dir/keep.off"
check "before/after table" has out "output (CGAL isotropic)"
check "output replaced" sh -c "head -1 '$dir/keep.off' | grep -q OFF"
check "report written" grep -q '"input"' "$dir/r.json"
check "svg written" grep -q "</svg>" "$dir/r.svg"
check "no temporary files left" sh -c "! ls -a '$dir' | grep -q partial"

# repaired by default: zero-area faces and non-manifold vertices (issue 25); refused with --strict
# (a tetrahedron whose bottom edge A-B is split at M on one side only, closed by the zero-area face A-M-B)
printf 'OFF\n5 6 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0.5 0 0\n3 0 2 4\n3 4 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 4 1\n' > "$dir/zero_area.off"
check "zero-area face repaired" run 0 "$poisson_remesh" --vertices 60 --quiet "$dir/zero_area.off" "$dir/zero_area_out.off"
check "repair reported" has err "1 degenerate faces were removed"
echo precious > "$dir/keep2.off"
check "strict refuses zero-area faces" run 1 "$poisson_remesh" --strict --vertices 60 "$dir/zero_area.off" "$dir/keep2.off"
check "strict names the faces" has err "degenerate (zero-area) faces"
check "output untouched (strict)" grep -q precious "$dir/keep2.off"
check "non-manifold vertices split" run 0 "$poisson_remesh" --vertices 800 --no-self-intersections --regrading 0 "$data/meshes/polygon_mesh.off" "$dir/polygon_mesh_out.off"
check "split reported" has err "2 non-manifold vertices"
check "non-manifold output written" sh -c "head -1 '$dir/polygon_mesh_out.off' | grep -q OFF"

# progress: on stderr in a terminal (script(1) gives the program one), nothing in a pipe
check "no progress in a pipe" run 0 "$poisson_remesh" --vertices 800 --no-self-intersections "$data/meshes/elephant.off" "$dir/p.off"
check "stderr of a piped run is empty" sh -c "! grep -q 'sampling' '$dir/err'"
if command -v script >/dev/null 2>&1; then
  check "progress in a terminal" sh -c "script -qec \"'$poisson_remesh' --vertices 800 --no-self-intersections '$data/meshes/elephant.off' '$dir/p.off'\" /dev/null > '$dir/tty' 2>&1"
  check "progress names the stages" sh -c "grep -q 'samples of about' '$dir/tty' && grep -q 'relaxation: round' '$dir/tty'"
  check "no progress with --quiet" sh -c "script -qec \"'$poisson_remesh' --quiet --vertices 800 --no-self-intersections '$data/meshes/elephant.off' '$dir/p.off'\" /dev/null > '$dir/tty' 2>&1 && ! grep -q 'samples of about' '$dir/tty'"
fi

# batch: ten inputs, one unreadable; nine outputs, a summary naming the bad one, exit code 1
mkdir -p "$dir/batch_in"
for m in elephant triceratops fandisk dino cow knot1 bull eight mushroom; do ln -s "$data/meshes/$m.off" "$dir/batch_in/$m.off"; done
cp "$dir/nan.off" "$dir/batch_in/broken.off"
check "batch with a bad file" run 1 "$poisson_remesh" --vertices 250 --no-self-intersections --regrading 0 -j 2 -o "$dir/batch_out" --summary "$dir/summary.csv" --summary-json "$dir/summary.json" "$dir/batch_in"
check "nine outputs" sh -c "[ \$(ls '$dir/batch_out' | grep -c '_remeshed.off\$') -eq 9 ]"
check "outputs are meshes" sh -c "for f in '$dir'/batch_out/*.off; do head -1 \"\$f\" | grep -q OFF || exit 1; done"
check "one line per file" sh -c "[ \$(grep -c '^\[[0-9]*/10\]' '$dir/out') -eq 10 ]"
check "the bad file is named" has out "broken.off: FAILED (bad input)"
check "summary has ten rows and a header" sh -c "[ \$(wc -l < '$dir/summary.csv') -eq 11 ]"
check "summary names the bad one" sh -c "grep 'broken.off' '$dir/summary.csv' | grep -q 'bad input'"
check "summary figures" sh -c "grep 'elephant.off' '$dir/summary.csv' | grep -q ',ok,'"
check "json summary" sh -c "grep -q '\"status\": \"bad input\"' '$dir/summary.json' && [ \$(grep -c '\"input\"' '$dir/summary.json') -eq 10 ]"
check "batch needs inputs" run 2 "$poisson_remesh" -o "$dir/batch_out"
check "one report file is not for a batch" run 2 "$poisson_remesh" --report "$dir/r.json" -o "$dir/batch_out" "$dir/batch_in"
check "all good: exit 0" run 0 "$poisson_remesh" --vertices 200 --no-self-intersections --regrading 0 -o "$dir/batch_ok" "$data/meshes/elephant.off" "$data/meshes/fandisk.off"

# poisson_sample
check "poisson_sample --help" run 0 "$poisson_sample" --help
check "poisson_sample needs a size" run 2 "$poisson_sample" "$data/meshes/elephant.off" "$dir/s.xyz"
check "poisson_sample bad features" run 2 "$poisson_sample" --vertices 100 --features sharp "$data/meshes/elephant.off" "$dir/s.xyz"
check "poisson_sample bad input" run 1 "$poisson_sample" --vertices 100 "$dir/nan.off" "$dir/s.xyz"
check "poisson_sample runs" run 0 "$poisson_sample" --vertices 500 --seed 3 "$data/meshes/elephant.off" "$dir/s.xyz"
check "one line per sample, three numbers" sh -c "n=\$(wc -l < '$dir/s.xyz'); [ \$n -gt 450 ] && [ \$n -lt 550 ] && awk 'NF != 3 { exit 1 }' '$dir/s.xyz'"
check "same seed, same file" sh -c "'$poisson_sample' --vertices 500 --seed 3 '$data/meshes/elephant.off' '$dir/t.xyz' 2>/dev/null && cmp -s '$dir/s.xyz' '$dir/t.xyz'"
check "adaptive samples with radii" run 0 "$poisson_sample" --vertices 400 --adaptive --radii --kinds "$data/meshes/elephant.off" "$dir/a.xyz"
check "five columns" sh -c "awk 'NF != 5 { exit 1 }' '$dir/a.xyz'"
check "radii vary" sh -c "awk '{ if(min == \"\" || \$5 < min) min = \$5; if(\$5 > max) max = \$5 } END { exit !(max > 2 * min) }' '$dir/a.xyz'"
check "spacing and kinds" run 0 "$poisson_sample" --spacing 0.05 --features none --kinds "$data/meshes/fandisk.off" "$dir/k.xyz"
check "kinds column" sh -c "awk 'NF != 4 { exit 1 }' '$dir/k.xyz'"

# geodesic_distances
check "geodesic_distances from a vertex" run 0 "$geodesic_distances" "$data/meshes/fandisk.off" --source-vertex 10 --radius 0.1
check "source at distance 0, two columns, sorted, all within R" sh -c "grep -q '^10 0\$' '$dir/out' && awk 'NF != 2 || \$2 > 0.1 || \$1 <= prev { exit 1 } { prev = \$1 }' prev=-1 '$dir/out'"
check "geodesic_distances from a face point" run 0 "$geodesic_distances" "$data/meshes/fandisk.off" --source-face 5 --bary 0.2 0.3 0.5 --radius 0.05
check "face source reaches its face's vertices" sh -c "[ \$(wc -l < '$dir/out') -ge 3 ]"
check "geodesic_distances bad index" run 2 "$geodesic_distances" "$data/meshes/fandisk.off" --source-vertex 99999999 --radius 0.1
check "geodesic_distances bad mesh" run 1 "$geodesic_distances" "$dir/nan.off" --source-vertex 0 --radius 0.1
check "geodesic_distances no radius" run 2 "$geodesic_distances" "$data/meshes/fandisk.off" --source-vertex 0

echo "command_line_programs: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
