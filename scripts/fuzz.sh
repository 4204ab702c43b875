#!/usr/bin/env bash
# Builds one libFuzzer target with clang (AddressSanitizer + UBSan, library code
# instrumented for coverage) into build-fuzz/ and runs it.
#
#   scripts/fuzz.sh TARGET [SECONDS] [libFuzzer options...]
#   scripts/fuzz.sh io_msh_fuzz 180
#
# Seeds come from tests/fuzz/seeds/NAME/ (TARGET without "_fuzz"); the growing corpus
# stays in build-fuzz/corpus/TARGET; crashing inputs and the log (fuzz-0.log) go to
# build-fuzz/findings/TARGET/.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
target=${1:?usage: scripts/fuzz.sh TARGET [SECONDS] [libFuzzer options...]}
seconds=${2:-60}
shift $(( $# >= 2 ? 2 : 1 ))
build_dir=${MIXMESH_FUZZ_BUILD_DIR:-$root/build-fuzz}

generator=()
[ -f "$build_dir/CMakeCache.txt" ] || generator=(-G Ninja)
cmake -S "$root" -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DMIXMESH_FUZZ=ON -DMIXMESH_TESTS=ON \
  -DMIXMESH_BENCHMARKS=OFF -DMIXMESH_WERROR=ON \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer" > /dev/null
cmake --build "$build_dir" --target "$target"

seeds="$root/tests/fuzz/seeds/${target%_fuzz}"
corpus="$build_dir/corpus/$target"
findings="$build_dir/findings/$target"
mkdir -p "$corpus" "$findings"
inputs=("$corpus")
[ -d "$seeds" ] && inputs+=("$seeds")
# With -jobs libFuzzer writes its log to fuzz-0.log in the working directory.
cd "$findings"
status=0
"$build_dir/tests/fuzz/$target" -max_total_time="$seconds" -jobs=1 -workers=1 -timeout=10 \
  -rss_limit_mb=2048 -artifact_prefix="$findings/" -print_final_stats=1 "$@" "${inputs[@]}" || status=$?
tail -n 25 "$findings/fuzz-0.log"
exit "$status"
