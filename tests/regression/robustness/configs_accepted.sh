#!/usr/bin/env bash
# Every config scripts/random-wings.py writes, in either design space, is one mixmesh
# accepts: its surface meshes (unknown keys, out-of-range values and sections that
# cross themselves are all errors there). Quick: the surface stage only.
#   configs_accepted.sh MIXMESH PYTHON OUTDIR COUNT SEED
set -euo pipefail
program=$1 python=$2 outdir=$3 count=$4 seed=$5
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
rm -rf "$outdir"
mkdir -p "$outdir"
for space in ordinary wide; do
  "$python" "$root/scripts/random-wings.py" "$count" "$seed" "$outdir/$space" --space "$space" > "$outdir/$space.txt"
  [ "$(wc -l < "$outdir/$space.txt")" -eq "$count" ] || { echo "configs_accepted: the $space space did not write $count configs" >&2; exit 1; }
  while read -r config; do
    "$program" surface --quiet "$config" -o "${config%.toml}.vtu"
  done < "$outdir/$space.txt"
done
echo "configs_accepted: $((2 * count)) configs, every surface built"
