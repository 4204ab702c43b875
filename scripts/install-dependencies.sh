#!/usr/bin/env bash
# Installs every package mixmesh builds, tests and benchmarks with, from Debian's
# repositories. Idempotent: packages already present are skipped by apt-get.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config ccache clang clang-format libclang-rt-14-dev
  libeigen3-dev libtet1.5-dev libcgal-dev libgmp-dev libmpfr-dev libopenmesh-dev
  libvtk9-dev libtomlplusplus-dev libcli11-dev libtbb-dev libnanoflann-dev libcgns-dev cgns-convert
  libgtest-dev libgmock-dev libbenchmark-dev
  python3 python3-numpy python3-scipy python3-meshio python3-vtk9 python3-matplotlib
  gmsh openfoam
)

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" \
    || missing+=("$package")
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "mixmesh: all dependencies are installed"
  exit 0
fi

sudo_prefix=()
[ "$(id -u)" -eq 0 ] || sudo_prefix=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_prefix[@]}" apt-get update -q
"${sudo_prefix[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
