#!/usr/bin/env bash
# Installs every Debian package that kasha's build, tests and scripts need. Idempotent; run as root
# (or with sudo available) on Debian 12.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  libembree-dev libopenexr-dev libnanoflann-dev libopenvdb-dev libnanovdb-dev libboost-iostreams-dev
  nlohmann-json3-dev libtinyobjloader-dev libassimp-dev zlib1g-dev libpng-dev libstb-dev libqoi-dev libcli11-dev libeigen3-dev
  libgtest-dev
  libopenmpi-dev openmpi-bin
  python3-numpy python3-matplotlib
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
