#!/usr/bin/env bash
# Installs Deltapath's build dependencies from Debian 12 packages (nothing is vendored
# or downloaded at build time). Uses sudo when not run as root.
set -euo pipefail
packages=(
  build-essential cmake ccache pkg-config
  libembree-dev libeigen3-dev libopenexr-dev libboost-random-dev libboost-math-dev
  libcgal-dev catch2 libyaml-cpp-dev libtbb-dev libcli11-dev libtinyobjloader-dev
  libstb-dev libfftw3-dev zlib1g-dev libpugixml-dev python3 python3-matplotlib chromium
  openmpi-bin libopenmpi-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
echo "installing: ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
