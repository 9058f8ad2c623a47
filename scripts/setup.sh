#!/usr/bin/env bash
# Installs every Debian package that building, testing and benchmarking ibl needs.
# Idempotent: run it as often as you like (root, or sudo available).
set -euo pipefail

packages=(
  # toolchain
  cmake ninja-build g++ clang-14 libclang-rt-14-dev clang-format pkg-config
  # libraries
  libopenexr-dev libimath-dev libstb-dev libpng-dev libglm-dev libcli11-dev libfmt-dev
  nlohmann-json3-dev libtbb-dev libtinygltf-dev libembree-dev libdraco-dev libmeshoptimizer-dev
  libvulkan-dev glslc mesa-vulkan-drivers vulkan-validationlayers libglfw3-dev
  # the viewer's window in tests, on a virtual X display
  xvfb xauth
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev python3
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  echo "setup: installing ${missing[*]}" >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup: all packages present" >&2
fi
