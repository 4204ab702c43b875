#!/usr/bin/env bash
# Set-up and the main job: installs, builds, then runs mixmesh on the default case.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/build.sh"
cd "$root"
mkdir -p out
"$root/build/bin/mixmesh" generate cases/onera_m6.toml --output-dir out
"$root/build/bin/mixmesh" check out/onera_m6.vtu --quiet
