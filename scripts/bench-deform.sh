#!/bin/sh
# ARA deformation of a 1 M-node hexahedral mesh: first run, cached repeat, checked step;
# median of three repetitions each. Usage: scripts/bench-deform.sh [BUILD_DIR]
set -eu
build=${1:-build}
ninja -C "$build" deform_ara_benchmark
"$build/tests/bench/deform_ara_benchmark" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
