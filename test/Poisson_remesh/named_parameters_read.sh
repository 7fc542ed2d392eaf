#!/usr/bin/env bash
# Every named parameter of the package (internal/parameters_interface.h) is read by the library
# (a get_parameter on its tag somewhere in include/ other than the parameter machinery), and every
# parameter named in the manual's table is one of the package's or one of CGAL's.
# Usage: named_parameters_read.sh SOURCE_DIR
set -u
src="$1"
interface="$src/include/Poisson_remesh/internal/parameters_interface.h"
passed=0; failed=0
for name in $(sed -n 's/^POISSON_REMESH_add_named_parameter([a-z_]*_t, \([a-z_]*\), [a-z_]*)$/\1/p' "$interface"); do
  if grep -rq --include=*.h "internal_np::$name\b" "$src/include" --exclude=parameters_interface.h --exclude=parameters.h; then
    passed=$((passed+1))
  else
    failed=$((failed+1)); echo "FAILED: named parameter '$name' is read nowhere"
  fi
done
# the manual's table: rows '| `name` | ...' (the first cell may list several names)
cgal_interface=/usr/include/CGAL/STL_Extension/internal/parameters_interface.h
for name in $(sed -n '/^## .*[Nn]amed parameters/,/^## /p' "$src/doc/Poisson_remesh/Poisson_remesh.md" | grep '^| `' | cut -d'|' -f2 | grep -o '`[a-z_]*`' | tr -d '`' | sort -u); do
  if grep -q "($name\b\|, $name)" "$interface" || grep -q ", $name)" "$cgal_interface"; then
    passed=$((passed+1))
  else
    failed=$((failed+1)); echo "FAILED: the manual names a parameter '$name' that does not exist"
  fi
done
echo "named_parameters: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
