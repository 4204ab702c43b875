#!/usr/bin/env bash
# Preconditioning measured on whole `mixmesh generate` runs: each config with
# farfield.precondition = false and = true, RUNS times each, the two interleaved so that
# both see the same machine load. Prints per config and setting the medians of the whole
# run and of the far-field stage (seconds, from --report), the tetrahedra, the largest
# dihedral angle, the tetrahedra above the sliver target and the hull-adjacent metric
# edges within [0.6, 1.6].
#
#   scripts/bench-precondition.sh [RUNS] CONFIG[:KEY=VALUE,...] ...
#
# Overrides after a colon go to --set (comma-separated), e.g.
#   scripts/bench-precondition.sh 3 cases/onera_m6.toml \
#     'cases/batch/wing_variants.toml:wing.naca="0015",wing.leading_edge_sweep=45.0,wing.taper=0.3,wing.tip_twist=-5.0'
# Builds nothing: runs $MIXMESH (default build/bin/mixmesh).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
program=${MIXMESH:-$root/build/bin/mixmesh}
[ -x "$program" ] || { echo "bench-precondition: $program not built (scripts/build.sh)" >&2; exit 2; }
runs=3
if [[ ${1:-} =~ ^[0-9]+$ ]]; then runs=$1; shift; fi
[ $# -gt 0 ] || { echo "usage: bench-precondition.sh [RUNS] CONFIG[:KEY=VALUE,...] ..." >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

median() { sort -g | awk '{ value[NR] = $1 } END { print (NR % 2) ? value[(NR + 1) / 2] : (value[NR / 2] + value[NR / 2 + 1]) / 2 }'; }
# The value of a top-level or [stages] key of a generate report.
report_value() { awk -v key="$2" -F' = ' '$1 == key { print $2; exit }' "$1"; }

printf '%-28s %-13s %8s %9s %10s %9s %9s %9s\n' case precondition run_s farfield_s tetrahedra dihedral above_tgt metric_in
for spec in "$@"; do
  config=${spec%%:*}
  overrides=()
  if [[ $spec == *:* ]]; then
    IFS=',' read -r -a pairs <<< "${spec#*:}"
    for pair in "${pairs[@]}"; do overrides+=(--set "$pair"); done
  fi
  name=$(basename "$config" .toml)
  [[ $spec == *:* ]] && name="$name*"
  for run in $(seq "$runs"); do
    for precondition in false true; do
      out=$work/$precondition-$run
      mkdir -p "$out"
      if ! "$program" generate "$config" "${overrides[@]}" --set "farfield.precondition=$precondition" \
          --output-dir "$out" --report "$out/report.toml" --quiet > "$out/log" 2>&1; then
        echo "bench-precondition: $name precondition=$precondition failed: $(tail -1 "$out/log")" >&2
        rm -f "$out/report.toml"
      fi
      rm -f "$out"/*.vtu "$out"/*.msh "$out"/*.su2 "$out"/*.cgns
    done
  done
  for precondition in false true; do
    reports=("$work/$precondition"-*/report.toml)
    [ -f "${reports[0]}" ] || { printf '%-28s %-13s failed\n' "$name" "$precondition"; continue; }
    run_s=$(for r in "${reports[@]}"; do [ -f "$r" ] && report_value "$r" seconds; done | median)
    farfield_s=$(for r in "${reports[@]}"; do [ -f "$r" ] && report_value "$r" farfield; done | median)
    first=${reports[0]}
    printf '%-28s %-13s %8.2f %9.2f %10s %9s %9s %9s\n' "$name" "$precondition" "$run_s" "$farfield_s" \
      "$(report_value "$first" tetrahedra)" "$(report_value "$first" largest_dihedral)" \
      "$(report_value "$first" tetrahedra_above_target_dihedral)" \
      "$(report_value "$first" hull_metric_edges_within_range)"
  done
  rm -rf "$work"/false-* "$work"/true-*
done
