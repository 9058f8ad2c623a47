#!/usr/bin/env bash
# KHR_materials_transmission with KHR_materials_volume against Blender Cycles 3.4
# (docs/materials.md, "Against Blender Cycles"): a solid glass sphere of index 1.5, white, clear or
# absorbing, under data/hdri/park.exr, 128 x 128, rendered by ibl's reference
# (`--transmission 1 --thickness 2`) and by Cycles' Glass BSDF (bench/cycles_scene.py --glass;
# an ico sphere of 163842 vertices, an absorbing one with a Volume Absorption shader of the same
# coefficient). Both single-scattering GGX (ibl --multiscatter off, Cycles' GGX), 16 bounces.
# Prints, for each roughness: the mean luminance ratio (ibl / Cycles), the frame and median 4 x 4
# block errors, each renderer's noise at SPP (the RMSE between its two seeds' renders) and its
# seconds (ibl: the whole command; Cycles: its render alone, cycles_render_seconds).
# The Fresnel terms differ on purpose: ibl's Schlick (F0 0.04), Cycles' exact dielectric Fresnel.
#
#   bash bench/cycles_transmission.sh IBL_BINARY [SPP]        (SPP: 1024 by default)
#
# Without `blender` on PATH (Debian: apt-get install blender) it says so and exits 0.
set -euo pipefail
IBL=${1:?usage: cycles_transmission.sh IBL_BINARY [SPP]}
SPP=${2:-1024}
NAME=cycles_transmission.sh
# shellcheck source=bench/cycles_common.sh
source "$(dirname "$0")/cycles_common.sh"
rmse() {  # the overall RMSE of $1 against $2
  "$IBL" compare "$1" "$2" | awk '/^overall/ { print $2 }'
}
seconds() {  # run a command, print its wall seconds
  local t0 t1
  t0=$(date +%s.%N)
  "$@"
  t1=$(date +%s.%N)
  python3 -c "print(f'{$t1 - $t0:.1f}')"
}
printf '%-10s %-5s %7s %9s %9s %10s %10s %7s %7s\n' glass r ratio frame median "ibl noise" "cy noise" "ibl s" "cy s"
for absorb in clear absorbing; do
  if [ $absorb = clear ]; then ia=(); ca=(); else
    ia=(--attenuation-color 0.8,0.6,0.4 --attenuation-distance 2)
    ca=(--attenuation-color 0.8,0.6,0.4 --attenuation-distance 2)
  fi
  for r in 0 0.2 0.5; do
    for seed in 1 2; do
      i="$OUT/ibl-$absorb-$r-$seed.exr" c="$OUT/cycles-$absorb-$r-$seed.exr"
      ti=$(seconds "$IBL" -q render sphere --env "$ENV_MAP" --metallic 0 --base-color 1,1,1 \
        --transmission 1 --thickness 2 --ior 1.5 --roughness "$r" "${ia[@]}" --multiscatter off \
        --bounces 16 --mode reference --size "$SIZE" --spp "$SPP" --tonemap none \
        --background 0,0,0 --seed "$seed" -o "$i")
      blender -b --factory-startup -P "$ROOT/bench/cycles_scene.py" -- \
        --env "$ENV_MAP" --size "$SIZE" --spp "$SPP" --roughness "$r" --glass 1.5 \
        --geometry mesh --bounces 16 --seed "$seed" "${ca[@]}" -o "$c" >"$c.log" 2>&1
    done
    i1="$OUT/ibl-$absorb-$r-1.exr" i2="$OUT/ibl-$absorb-$r-2.exr"
    c1="$OUT/cycles-$absorb-$r-1.exr" c2="$OUT/cycles-$absorb-$r-2.exr"
    ratio=$(python3 -c "print(f'{$(luminance "$i1") / $(luminance "$c1"):.4f}')")
    frame=$("$IBL" -q compare "$i1" "$c1" --json | python3 -c '
import json, sys; f = json.load(sys.stdin)["frame"]
e, m = 100 * f["frame_error"], 100 * f["median_block_error"]
print(f"{e:7.2f} % {m:7.2f} %")')
    printf '%-10s %-5s %7s %s %10s %10s %7s %7s\n' "$absorb" "$r" "$ratio" "$frame" \
      "$(rmse "$i1" "$i2")" "$(rmse "$c1" "$c2")" "$ti" "$(grep -m1 render_seconds "$c2.log" | awk '{print $2}')"
  done
done
