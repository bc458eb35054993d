#!/usr/bin/env bash
# GL calls live in the GL layer (docs/ARCHITECTURE.md): none in apps/, and
# at most LIMIT raw gl:: entry points (gl::CapitalName) outside mvr/gl/.
# Prints the count per file and exits 1 over the limit.
#   tests/floors/check_gl_calls.sh [SOURCE_DIR] [LIMIT]
set -euo pipefail
cd "${1:-$(dirname "$0")/../..}"
limit=${2:-100}
calls() { grep -oE '\bgl::[A-Z][A-Za-z0-9]*\(' "$@" | grep -vE 'gl::(Texture|Buffer|Program|Framebuffer|VertexArray)\(' || true; }
apps=$(find apps -name '*.cpp' -o -name '*.h' | sort | xargs grep -lE '\bgl::[A-Z][A-Za-z0-9]*\(' | grep -v '^$' || true)
outside=$(find mvr epi slicing shading apps \( -name '*.cpp' -o -name '*.h' \) -not -path 'mvr/gl/*' | sort)
total=$(calls $outside | wc -l)
bad=0
for f in $apps; do
  n=$(calls "$f" | wc -l)
  if (( n > 0 )); then echo "gl calls: $f: $n raw gl:: calls in apps/ (use the GL layer, mvr/gl)"; bad=1; fi
done
echo "gl calls: $total raw gl:: calls outside mvr/gl (at most $limit)"
(( total <= limit )) || bad=1
exit $bad
