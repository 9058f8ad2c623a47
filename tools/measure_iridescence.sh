#!/usr/bin/env bash
# KHR_materials_iridescence: the split sum against the path-traced reference (docs/materials.md,
# "Iridescence", "Measured"). A thin film of index 1.3 over dark glass (base color 0.02, r =
# 0.15: a soap film's colors) and over a gold-like metal (base color 0.9 0.6 0.3, r = 0.35), at
# three thicknesses, each after the same sphere without a film, under two HDRIs (park, sunset)
# and one analytic light (a point light, no environment); prints `ibl compare`'s frame error and
# median 4 x 4 block error for each. Outputs already present are kept (delete OUT to start
# over). Environment: IBL (default build-dev/ibl), OUT (default out/iridescence), SIZE
# (128x128), REF_SPP (1024).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-out/iridescence}
source tools/measure_common.sh
printf '%-8s %-6s %-10s %10s %10s\n' light base thickness frame median
for light in park sunset point; do
  lightingFor "$light"
  for base in glass metal; do
    if [ "$base" = glass ]; then
      material=(--base-color 0.02,0.02,0.02 --metallic 0 --roughness 0.15)
    else
      material=(--base-color 0.9,0.6,0.3 --metallic 1 --roughness 0.35)
    fi
    for thickness in none 250 420 700; do
      name="$OUT/$light-$base-$thickness"
      film=()
      [ "$thickness" = none ] || film=(--iridescence 1 --iridescence-thickness "$thickness")
      args=(sphere "${lighting[@]}" --size "$SIZE" "${material[@]}" "${film[@]}"
            --background 0,0,0 --quiet)
      [ -f "$name-ref.exr" ] || "$IBL" render "${args[@]}" --mode reference --spp "$REF_SPP" \
        -o "$name-ref.exr"
      [ -f "$name-rt.exr" ] || "$IBL" render "${args[@]}" --spp 16 -o "$name-rt.exr"
      printf '%-8s %-6s %-10s %s\n' "$light" "$base" "$thickness" "$(figures "$name-rt.exr" "$name-ref.exr")"
    done
  done
done
