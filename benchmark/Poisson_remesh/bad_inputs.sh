#!/usr/bin/env bash
# Runs the command-line remesher on each kind of bad input and prints a Markdown table: what was
# tried, the exit code, the first line of the message, and whether an existing output file was
# left intact. Usage: bad_inputs.sh [POISSON_REMESH]   (default: ../../build/examples/Poisson_remesh/poisson_remesh)
set -u
prog="${1:-$(dirname "$0")/../../build/examples/Poisson_remesh/poisson_remesh}"
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
printf '' > "$dir/empty.off"
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n' > "$dir/truncated.off"
head -c 3000 /dev/urandom > "$dir/garbage.off"
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\n' > "$dir/garbage.ply"; head -c 200 /dev/urandom >> "$dir/garbage.ply"
printf 'OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n' > "$dir/nan.off"
printf 'v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n' > "$dir/inf.obj"
printf 'OFF\n0 0 0\n' > "$dir/no_faces.off"
# three triangles on one edge: a non-manifold edge
printf 'OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n' > "$dir/nonmanifold_edge.off"
# two tetrahedra sharing one vertex: a non-manifold vertex
printf 'OFF\n7 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n-1 0 0\n0 -1 0\n0 0 -1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 4 5\n3 0 5 6\n3 0 6 4\n3 4 6 5\n' > "$dir/nonmanifold_vertex.off"
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 0 1\n' > "$dir/repeated_vertex.off"
printf 'hello\n' > "$dir/mesh.xyz"
mkdir "$dir/a_directory.off"

echo "| input | exit code | message (first line) | existing output intact |"
echo "|---|---:|---|:-:|"
try() { # try LABEL INPUT [OUTPUT]
  local label="$1" input="$2" out="${3:-$dir/out.off}"
  [ -n "${3:-}" ] || echo precious > "$out"
  "$prog" --vertices 500 "$input" "$out" > "$dir/stdout" 2> "$dir/stderr"; local code=$?
  local msg; msg=$(grep -v '^$' "$dir/stderr" | head -1 | sed 's/|/\\|/g; s#'"$dir"'/##g')
  local intact="n/a"
  [ -n "${3:-}" ] || { grep -q precious "$out" 2>/dev/null && intact=yes || intact=NO; }
  echo "| $label | $code | ${msg:-–} | $intact |"
}
try "missing file" "$dir/none.off"
try "a directory" "$dir/a_directory.off"
try "empty file" "$dir/empty.off"
try "truncated OFF" "$dir/truncated.off"
try "binary garbage (.off)" "$dir/garbage.off"
try "binary garbage (.ply)" "$dir/garbage.ply"
try "unsupported extension" "$dir/mesh.xyz"
try "NaN coordinate" "$dir/nan.off"
try "infinite coordinate (OBJ)" "$dir/inf.obj"
try "no faces" "$dir/no_faces.off"
try "non-manifold edge" "$dir/nonmanifold_edge.off"
try "non-manifold vertex" "$dir/nonmanifold_vertex.off"
try "face with a repeated vertex" "$dir/repeated_vertex.off"
try "unwritable output path" "$(dirname "$0")/../../build/data/meshes/elephant.off" "$dir/no/such/dir/out.off"
