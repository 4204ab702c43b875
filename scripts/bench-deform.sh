#!/bin/sh
# ARA deformation of a 1 M-node hexahedral mesh: first run and cached repeat (argument /0:
# conjugate gradients, /1: Gauss–Seidel, /2: conjugate gradients to a 100x tighter
# tolerance) and the checked step; median of three
# repetitions each, with wall and CPU time of the whole run and the load before and after
# (the timings mean little on a loaded machine).
# Usage: scripts/bench-deform.sh [BUILD_DIR] [BENCHMARK_FILTER]
set -eu
build=${1:-build}
filter=${2:-.}
ninja -C "$build" deform_ara_benchmark
echo "load before: $(cat /proc/loadavg)"
/usr/bin/time -v "$build/tests/bench/deform_ara_benchmark" --benchmark_filter="$filter" \
  --benchmark_repetitions=3 --benchmark_report_aggregates_only=true --benchmark_counters_tabular=true
echo "load after: $(cat /proc/loadavg)"
