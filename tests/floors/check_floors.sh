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
  [mvr/gl]=1 [mvr/files]=1
  [mvr/images]=2
  [mvr/assets]=3 [mvr/frames]=3
  [shading]=4
  [mvr/views]=5
  [slicing]=6 [slicing/gpu]=6
  [epi]=7 [epi/gpu]=7
  [mvr/backends/mvr]=8 [mvr/backends/interp]=8 [mvr/backends/warp]=8
  [mvr/backends/svr]=8 [mvr/backends/deferred]=8
  [mvr/backends]=9
  [apps/cli]=10 [apps/scenes]=10
  [apps/render]=11 [apps/bench]=11 [apps/native]=11 [apps/viewer]=11 [apps/helpers]=11
  [apps/live]=12
  [apps]=13
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
