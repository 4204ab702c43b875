#!/usr/bin/env bash
# Installs the dependencies and builds mixmesh in Release into build/ (reused on a
# second run). Extra arguments go to CMake's configure step.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${MIXMESH_BUILD_DIR:-$root/build}

"$root/scripts/install-dependencies.sh"
generator=()
[ -f "$build_dir/CMakeCache.txt" ] || generator=(-G Ninja)
cmake -S "$root" -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DMIXMESH_WERROR=ON "$@"
cmake --build "$build_dir" --parallel "$(nproc)"
