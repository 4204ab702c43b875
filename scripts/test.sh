#!/usr/bin/env bash
# Set-up and the whole test suite: installs, builds in Release with warnings as
# errors and runs every test CI runs (all but the "heavy" label), then builds the
# unit tests with AddressSanitizer and UndefinedBehaviorSanitizer and runs them.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
jobs=$(nproc)

"$root/scripts/build.sh"
ctest --test-dir "$root/build" --label-exclude heavy --output-on-failure --parallel "$jobs"

sanitize_dir="$root/build-sanitize"
generator=()
[ -f "$sanitize_dir/CMakeCache.txt" ] || generator=(-G Ninja)
cmake -S "$root" -B "$sanitize_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DMIXMESH_WERROR=ON -DMIXMESH_SANITIZE=ON -DMIXMESH_BENCHMARKS=OFF
cmake --build "$sanitize_dir" --parallel "$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir "$sanitize_dir" --label-regex unit --output-on-failure --parallel "$jobs"
