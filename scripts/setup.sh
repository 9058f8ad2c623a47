#!/usr/bin/env bash
# Installs every Debian package that building, testing and benchmarking ibl needs, and the npm
# packages of the engine tests (tests/engines/package-lock.json: the engines and the browser
# driver, pinned; Debian's chromium is the browser). Idempotent: run it as often as you like
# (root, or sudo available).
set -euo pipefail

packages=(
  # toolchain
  cmake ninja-build g++ clang-14 libclang-rt-14-dev clang-format pkg-config
  # libraries
  libopenexr-dev libimath-dev libstb-dev libpng-dev libglm-dev libcli11-dev libfmt-dev
  nlohmann-json3-dev libtbb-dev libtinygltf-dev libembree-dev libdraco-dev libmeshoptimizer-dev
  libwebp-dev
  libvulkan-dev glslc mesa-vulkan-drivers vulkan-validationlayers libglfw3-dev
  # the viewer's panel (Dear ImGui with its GLFW and Vulkan back ends)
  libimgui-dev
  # the viewer's window in tests, on a virtual X display
  xvfb xauth
  # pressing the window's keys and clicking its panel in tests; Xlib for the tests' own
  # drag-and-drop source (tests/support/xdnd_drop.cpp)
  xdotool libx11-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev python3 python3-yaml
  # the Python module (python/) and its tests
  pybind11-dev python3-dev python3-numpy
  # the Debian packages (cpack: dpkg-shlibdeps, file; Debian's checker lintian, run by the
  # install tests) and the completion tests (zsh)
  dpkg-dev file lintian zsh
  # the engine targets rendered by the engines in a headless browser (scripts/engines.sh)
  chromium
  # probe grids and batch bakes as array jobs on a single-node Slurm cluster (scripts/cluster.sh)
  slurm-wlm munge
)
# Node.js and npm for the engine tests: the machine's own if it has them, else Debian's (checked
# for version 20 below).
command -v node >/dev/null && command -v npm >/dev/null || packages+=(nodejs npm)

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

# The engine tests' npm packages, exactly as locked; again only when the lock file changed.
# playwright-core (the browser driver) needs Node.js 20 or newer.
node_major="$(node -p 'process.versions.node.split(".")[0]')"
if ((node_major < 20)); then
  echo "setup: the engine tests need Node.js >= 20 (playwright-core); this machine has $(node --version)" >&2
  exit 1
fi
engines="$(dirname "$0")/../tests/engines"
lock_hash="$(sha256sum "$engines/package-lock.json" | cut -d' ' -f1)"
if [ "$(cat "$engines/node_modules/.ibl-lock-hash" 2>/dev/null)" != "$lock_hash" ]; then
  echo "setup: installing the engine tests' npm packages (tests/engines/package-lock.json)" >&2
  npm ci --prefix "$engines" --ignore-scripts --no-audit --no-fund --loglevel=error >/dev/null
  echo "$lock_hash" >"$engines/node_modules/.ibl-lock-hash"
else
  echo "setup: engine tests' npm packages present" >&2
fi
