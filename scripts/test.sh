#!/usr/bin/env bash
# Set-up and the whole test suite: installs, builds in Release with warnings as
# errors and runs every test CI runs (all but the "heavy" label), the "slurm" ones
# against a one-node Slurm it installs and starts (scripts/slurm-cluster.sh), then
# builds the unit tests with AddressSanitizer and UndefinedBehaviorSanitizer and
# runs them.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
jobs=$(nproc)

"$root/scripts/build.sh"
ctest --test-dir "$root/build" --label-exclude 'heavy|slurm' --output-on-failure --parallel "$jobs"

# A machine where Slurm cannot be installed or started still runs every other test.
# The trap stops whatever part of Slurm did start, even when ctest fails.
slurm_log="$root/build/slurm-cluster.log"
trap '"$root/scripts/slurm-cluster.sh" stop > /dev/null 2>&1' EXIT
if "$root/scripts/slurm-cluster.sh" install > "$slurm_log" 2>&1 \
  && "$root/scripts/slurm-cluster.sh" start >> "$slurm_log" 2>&1; then
  ctest --test-dir "$root/build" --label-regex slurm --output-on-failure
else
  echo "test.sh: the slurm tests did not run, Slurm could not be started here: $(tail -n 1 "$slurm_log") (all of it in $slurm_log)"
fi
"$root/scripts/slurm-cluster.sh" stop > /dev/null 2>&1
trap - EXIT

sanitize_dir="$root/build-sanitize"
generator=()
[ -f "$sanitize_dir/CMakeCache.txt" ] || generator=(-G Ninja)
cmake -S "$root" -B "$sanitize_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DMIXMESH_WERROR=ON -DMIXMESH_SANITIZE=ON -DMIXMESH_BENCHMARKS=OFF
cmake --build "$sanitize_dir" --parallel "$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir "$sanitize_dir" --label-regex unit --output-on-failure --parallel "$jobs"
