#!/usr/bin/env bash
# Set-up and the main job: installs, builds, then runs mixmesh on the default case.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/build.sh"
cd "$root"
"$root/build/bin/mixmesh" check cases/meshes/four_types.vtu
