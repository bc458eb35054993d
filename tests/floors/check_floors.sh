#!/usr/bin/env bash
# The floors of docs/ARCHITECTURE.md, enforced: a folder's code includes
# only its own floor and the floors below it. Prints every include that
# reaches up and exits 1 if there is one.
#   tests/floors/check_floors.sh [SOURCE_DIR]
set -euo pipefail
cd "${1:-$(dirname "$0")/../..}"
# Lowest first; folders on one floor do not include each other (the map
# lists them apart where they must not).
declare -A floor=(
  [mvr]=0
  [mvr/gl]=1 [mvr/io]=1
  [mvr/frames]=2
  [shading]=3
  [mvr/views]=4
  [slicing]=5 [slicing/gpu]=5
  [epi]=6 [epi/gpu]=6
  [mvr/backends/mvr]=7 [mvr/backends/interp]=7 [mvr/backends/warp]=7
  [mvr/backends/svr]=7 [mvr/backends/deferred]=7
  [mvr/backends]=8
  [apps]=9
)
bad=0
while IFS= read -r file; do
  from=$(dirname "$file")
  [[ -n "${floor[$from]:-}" ]] || { echo "floors: $file: folder $from has no floor (add it to this map and docs/ARCHITECTURE.md)"; bad=1; continue; }
  while IFS= read -r inc; do
    to=$(dirname "$inc")
    [[ -n "${floor[$to]:-}" ]] || continue  # tests/, third-party
    if (( floor[$to] > floor[$from] )) || { [[ $to != "$from" ]] && (( floor[$to] == floor[$from] )) &&
                                            [[ ${to%/gpu} != "${from%/gpu}" ]]; }; then
      echo "floors: $file includes $inc: $to (floor ${floor[$to]}) is not below $from (floor ${floor[$from]})"
      bad=1
    fi
  done < <(sed -n 's/^#include "\([a-z_/]*\.h\)".*/\1/p' "$file")
done < <(find mvr epi slicing shading apps -name '*.h' -o -name '*.cpp' | sort)
exit $bad
