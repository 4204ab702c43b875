#!/usr/bin/env bash
# End-to-end timing of `mixmesh check` on a ~0.9 M-cell mixed mesh (hexahedra and
# prisms in layers, a pyramid/tetrahedron transition, tetrahedra above), written to
# .vtu by the benchmark program. Runs the check RUNS times (default 5) and prints the
# median of the wall time and of the read, validity and quality times the command
# reports in its JSON.
#
#   scripts/bench-check.sh [BUILD_DIR] [RUNS] [SIZE]
#
# BUILD_DIR defaults to build/ (needs the targets mixmesh-cli and
# quality_check_benchmark); SIZE 63 gives 1 025 829 cells.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${1:-$root/build}
runs=${2:-5}
size=${3:-63}
program=$build_dir/bin/mixmesh
generator=$build_dir/tests/bench/quality_check_benchmark
for file in "$program" "$generator"; do
  [ -x "$file" ] || { echo "bench-check: $file not built (ninja -C $build_dir mixmesh-cli quality_check_benchmark)" >&2; exit 2; }
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$generator" --write-mesh="$work/mesh.vtu" --size="$size"

for run in $(seq "$runs"); do
  start=$(date +%s.%N)
  status=0
  "$program" check "$work/mesh.vtu" --quiet --json "$work/report-$run.json" > /dev/null || status=$?
  end=$(date +%s.%N)
  [ "$status" -eq 0 ] || { echo "bench-check: mixmesh check exited with $status" >&2; exit 1; }
  echo "$start $end" > "$work/wall-$run.txt"
done

/usr/bin/python3 - "$work" "$runs" <<'PYTHON'
import json, statistics, sys
work, runs = sys.argv[1], int(sys.argv[2])
rows = {"wall": [], "read": [], "validity": [], "quality": []}
for run in range(1, runs + 1):
    start, end = map(float, open(f"{work}/wall-{run}.txt").read().split())
    report = json.load(open(f"{work}/report-{run}.json"))
    rows["wall"].append(end - start)
    for key in ("read", "validity", "quality"):
        rows[key].append(report["timings"][f"{key}_seconds"])
counts = report["counts"]
cells = sum(counts[name] for name in ("tetrahedron", "pyramid", "prism", "hexahedron"))
print(f"mixmesh check: {cells} cells, {counts['points']} points, {runs} runs, medians:")
for key, values in rows.items():
    print(f"  {key:9s} {statistics.median(values):7.3f} s   (min {min(values):.3f}, max {max(values):.3f})")
check = [v + q for v, q in zip(rows["validity"], rows["quality"])]
print(f"  check     {statistics.median(check):7.3f} s   (validity + quality)")
PYTHON
