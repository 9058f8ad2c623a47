#!/usr/bin/env bash
# KHR_materials_ior against Blender Cycles 3.4 (docs/materials.md, "Against Blender Cycles"): a
# black dielectric sphere (no diffuse: the specular lobe alone) of index N under
# data/hdri/park.exr, 128 x 128, rendered by ibl's reference and by Cycles' Principled BSDF with
# Specular = F0(N) / 0.08 (Cycles' F0 = 0.08 Specular), Specular Tint 0, both single-scattering GGX
# (and both with multiple scattering: ibl's walk, Cycles' MULTI_GGX). Prints `ibl compare`'s
# mean luminance ratio (ibl / Cycles) and median 4 x 4 block error for each index and roughness.
# The two Fresnel curves differ on purpose: ibl's Schlick between F0 and 1, Cycles' the exact
# dielectric Fresnel rescaled to start at F0.
#
#   bash bench/cycles_dielectric.sh IBL_BINARY [SPP]        (SPP: 512 by default)
#
# Without `blender` on PATH (Debian: apt-get install blender) it says so and exits 0.
set -euo pipefail
IBL=${1:?usage: cycles_dielectric.sh IBL_BINARY [SPP]}
SPP=${2:-512}
NAME=cycles_dielectric.sh
# shellcheck source=bench/cycles_common.sh
source "$(dirname "$0")/cycles_common.sh"
figures() {  # figures IBL CYCLES: the ratio of their means, frame and median block error
  local a b ratio
  a=$(luminance "$1")
  b=$(luminance "$2")
  ratio=$(python3 -c "print(f'{$a / $b:.4f}')")
  "$IBL" -q compare "$1" "$2" --json | python3 -c '
import json, sys; f = json.load(sys.stdin)["frame"]
e, m = 100 * f["frame_error"], 100 * f["median_block_error"]
print(f"{sys.argv[1]:>7} {e:7.2f} % {m:7.2f} %")' "$ratio"
}
printf '%-6s %-5s %-6s %7s %9s %9s\n' ior r scatter ratio frame median
for ior in 1.33 1.5 2.42; do
  f0=$(python3 -c "print(((${ior} - 1) / (${ior} + 1)) ** 2)")
  for r in 0.2 0.5; do
    for scatter in single multi; do
      if [ $scatter = single ]; then ms=(--multiscatter off); cy=(); else ms=(); cy=(--multiscatter); fi
      i="$OUT/ibl-$ior-$r-$scatter.exr" c="$OUT/cycles-$ior-$r-$scatter.exr"
      "$IBL" -q render sphere --env "$ENV_MAP" --metallic 0 --base-color 0,0,0 --ior "$ior" \
        --roughness "$r" "${ms[@]}" --mode reference --size "$SIZE" --spp "$SPP" --tonemap none \
        --background 0,0,0 -o "$i"
      blender -b --factory-startup -P "$ROOT/bench/cycles_scene.py" -- --env "$ENV_MAP" \
        --size "$SIZE" --spp "$SPP" --roughness "$r" --dielectric-f0 "$f0" "${cy[@]}" \
        -o "$c" >"$c.log" 2>&1
      printf '%-6s %-5s %-6s %s\n' "$ior" "$r" "$scatter" "$(figures "$i" "$c")"
    done
  done
done
