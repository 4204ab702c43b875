#!/usr/bin/env bash
# Wall time of `mixmesh batch` one case at a time against JOBS at a time, median of
# RUNS runs each, on a config whose swept keys expand into a few small cases.
#
#   scripts/bench-batch.sh [BUILD_DIR] [RUNS] [JOBS] [CONFIG]
#
# Defaults: build/, 3 runs, 2 jobs, cases/batch/four_wings.toml (4 cases).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${1:-$root/build}
runs=${2:-3}
jobs=${3:-2}
config=${4:-$root/cases/batch/four_wings.toml}
program=$build_dir/bin/mixmesh
[ -x "$program" ] || { echo "bench-batch: $program not built (scripts/build.sh)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

median() { sort -g | awk '{ value[NR] = $1 } END { print (NR % 2) ? value[(NR + 1) / 2] : (value[NR / 2] + value[NR / 2 + 1]) / 2 }'; }

for parallel in 1 "$jobs"; do
  : > "$work/times-$parallel"
  for run in $(seq "$runs"); do
    output=$work/run-$parallel-$run
    start=$(date +%s.%N)
    status=0
    "$program" batch "$config" -j "$parallel" -o "$output" > "$work/log" 2>&1 || status=$?
    end=$(date +%s.%N)
    if [ "$status" -ne 0 ]; then
      echo "bench-batch: -j $parallel run $run: $status case(s) failed, see $output/summary.csv" >&2
      cat "$work/log" >&2
      exit 1
    fi
    awk -v start="$start" -v end="$end" 'BEGIN { print end - start }' >> "$work/times-$parallel"
  done
  cases=$(($(wc -l < "$output/summary.csv") - 1))
  printf -- '-j %s: %s cases, wall seconds %s (median of %s: %.2f)\n' "$parallel" "$cases" \
    "$(tr '\n' ' ' < "$work/times-$parallel")" "$runs" "$(median < "$work/times-$parallel")"
done
