#!/bin/sh
# A first and a repeat `mixmesh deform` run: RUNS times each (median printed), the first
# without the ARA cache file (nearest faces searched, geometry built, file written), the
# repeat with it. MOTION must name CACHE as its [ara] cache. Wall and CPU seconds of the
# whole command, the ARA stage's own seconds (-v), and the load before and after.
# Usage: scripts/bench-deform-repeat.sh BUILD_DIR MESH MOTION CACHE [RUNS]
set -eu
build=$1 mesh=$2 motion=$3 cache=$4 runs=${5:-3}
grep -q "cache *= *\"$cache\"" "$motion" || { echo "$motion does not name $cache as its cache" >&2; exit 2; }
program="$build/bin/mixmesh"
output=$(mktemp -d)
trap 'rm -rf "$output"' EXIT
median() { sort -g | awk '{ value[NR] = $1 } END { print value[int((NR + 1) / 2)] }'; }
echo "load before: $(cat /proc/loadavg)"
for kind in first repeat; do
  : > "$output/wall" ; : > "$output/ara"
  for run in $(seq "$runs"); do
    [ "$kind" = first ] && rm -f "$cache"
    [ "$kind" = repeat ] && [ ! -f "$cache" ] && "$program" deform "$mesh" --motion "$motion" -o "$output/out.vtu" > /dev/null
    /usr/bin/time -f "%e %U %S" -o "$output/time" "$program" deform "$mesh" --motion "$motion" -o "$output/out.vtu" -v > "$output/log"
    read -r wall user system < "$output/time"
    ara=$(sed -n 's/.*step 1\/[0-9]* (ara): \([0-9.e+-]*\) s.*/\1/p' "$output/log" | head -1)
    echo "$kind run $run: wall $wall s, CPU $(awk "BEGIN { print $user + $system }") s, ARA $ara s"
    echo "$wall" >> "$output/wall"; echo "$ara" >> "$output/ara"
  done
  echo "$kind: median wall $(median < "$output/wall") s, median ARA $(median < "$output/ara") s"
done
echo "load after: $(cat /proc/loadavg)"
