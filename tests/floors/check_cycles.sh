#!/usr/bin/env bash
# The structure is a stack (docs/ARCHITECTURE.md): no two nouns (a file's
# .h and .cpp together) include each other, directly or around a loop, so
# the drawing of who includes whom has no arrow back up. tsort finds the
# loops; prints each and exits 1 if there is one.
#   tests/floors/check_cycles.sh [SOURCE_DIR]
set -euo pipefail
cd "${1:-$(dirname "$0")/../..}"
edges=$(find mvr epi slicing shading apps \( -name '*.h' -o -name '*.cpp' \) | sort | while IFS= read -r f; do
  sed -n 's/^#include "\([a-z_/]*\)\.h".*/\1/p' "$f" | while IFS= read -r to; do
    [[ $to != "${f%.*}" ]] && echo "$to ${f%.*}"
  done
done)
if loops=$(tsort <<<"$edges" 2>&1 >/dev/null) && [[ -z $loops ]]; then
  echo "cycles: none"
  exit 0
fi
echo "cycles: includes that loop back (each a noun that reaches up to one that includes it):"
echo "$loops"
exit 1
