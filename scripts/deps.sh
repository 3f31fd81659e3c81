#!/usr/bin/env bash
# Installs the Debian packages cavelight needs, if any is missing. Sourced by test.sh and
# demo.sh. Runs apt-get update once, only when something must be installed.
set -euo pipefail

CAVELIGHT_PACKAGES=(
  build-essential cmake pkg-config git
  libcmocka-dev libcjson-dev libpng-dev zlib1g-dev libzip-dev libxml2-dev
  libtinygltf-dev nlohmann-json3-dev libstb-dev libdraco-dev draco
  libzmq3-dev libusb-1.0-0-dev
  libegl-dev libegl1-mesa-dev libgl1-mesa-dri libosmesa6-dev libglfw3-dev libxrandr-dev
  libembree-dev gnuplot-nox clang libclang-rt-14-dev iproute2 xvfb python3 apitrace
)

cavelight_install_deps() {
  local missing=()
  for p in "${CAVELIGHT_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "cavelight: installing ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# cavelight_build ROOT [DIR [CMAKE-ARGS...]]: configures and builds ROOT into ROOT/DIR
# (default build/, Release).
cavelight_build() {
  local root=$1 dir=${2:-build}
  shift $(( $# < 2 ? $# : 2 ))
  cmake -S "$root" -B "$root/$dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
  cmake --build "$root/$dir" -j "$(nproc)"
}
