#!/usr/bin/env bash
# The engine targets in the engines themselves (docs/targets.md, "In the engines themselves"):
# bakes a real HDRI for Filament, Babylon.js and the glTF Sample Viewer, renders spheres with
# each engine's own loader in headless Chromium (SwiftShader WebGL 2) and compares them with
# `ibl render` (split sum and path-traced reference) and with the engine's own prefiltering.
# Assumes scripts/setup.sh (npm ci in tests/engines, Debian's chromium) and a build of `ibl`
# (IBL_BUILD, default build/). IBL_ENGINES_TIMEOUT_S bounds the whole run (default 900 s).
# Options go to tests/engines/run.mjs: --work DIR (default out/engines), --docs (rewrite the
# measured section of docs/targets.md and docs/images/engines.png), --only ENGINE,...
set -euo pipefail
cd "$(dirname "$0")/.."
exec node tests/engines/run.mjs --ibl "${IBL_BUILD:-build}/ibl" "$@"
