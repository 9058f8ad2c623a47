#!/usr/bin/env bash
# KHR_materials_anisotropy: the split sum against the path-traced reference (docs/materials.md,
# "Anisotropy", "Measured"). A brushed metal (base color 0.95 0.64 0.54) and a dielectric (base
# color 0.2 0.3 0.5), each at roughness 0.25 and 0.5, without anisotropy and at strengths 0.5 and
# 1 along the sphere's parallels, under two HDRIs (park, sunset) and one analytic light (a point
# light, no environment); prints `ibl compare`'s frame error and median 4 x 4 block error for
# each. Outputs already present are kept (delete OUT to start over). Environment: IBL (default
# build-dev/ibl), OUT (default out/anisotropy), SIZE (128x128), REF_SPP (1024).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-out/anisotropy}
source tools/measure_common.sh
printf '%-8s %-6s %-9s %-8s %10s %10s\n' light base roughness strength frame median
for light in park sunset point; do
  lightingFor "$light"
  for base in metal dielectric; do
    if [ "$base" = metal ]; then
      color=(--base-color 0.95,0.64,0.54 --metallic 1)
    else
      color=(--base-color 0.2,0.3,0.5 --metallic 0)
    fi
    for roughness in 0.25 0.5; do
      for strength in 0 0.5 1; do
        name="$OUT/$light-$base-$roughness-$strength"
        args=(sphere "${lighting[@]}" --size "$SIZE" "${color[@]}" --roughness "$roughness"
              --anisotropy "$strength" --background 0,0,0 --quiet)
        [ -f "$name-ref.exr" ] || "$IBL" render "${args[@]}" --mode reference --spp "$REF_SPP" \
          -o "$name-ref.exr"
        [ -f "$name-rt.exr" ] || "$IBL" render "${args[@]}" --spp 16 -o "$name-rt.exr"
        printf '%-8s %-6s %-9s %-8s %s\n' "$light" "$base" "$roughness" "$strength" \
          "$(figures "$name-rt.exr" "$name-ref.exr")"
      done
    done
  done
done
