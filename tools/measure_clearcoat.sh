#!/usr/bin/env bash
# KHR_materials_clearcoat: the split sum against the path-traced reference (docs/materials.md,
# "Clear coat", "Measured"). A red dielectric sphere (base color 0.6 0.05 0.05, r = 0.5, the
# paint) without a coat, then under one that sweeps its roughness at full strength and at half
# strength, under two HDRIs (park, sunset) and one analytic light (a point light, no
# environment); prints `ibl compare`'s frame error and median 4 x 4 block error for each.
# Outputs already present are kept (delete OUT to start over).
# Environment: IBL (default build-dev/ibl), OUT (default out/clearcoat), SIZE (128x128),
# REF_SPP (1024).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-out/clearcoat}
source tools/measure_common.sh
printf '%-8s %-10s %-10s %10s %10s\n' light clearcoat roughness frame median
for light in park sunset point; do
  lightingFor "$light"
  for coat in "0 0" "1 0" "1 0.1" "1 0.3" "1 0.6" "0.5 0.1"; do
    read -r strength rc <<< "$coat"
    name="$OUT/$light-c$strength-r$rc"
    args=(sphere "${lighting[@]}" --size "$SIZE" --base-color 0.6,0.05,0.05 --metallic 0
          --roughness 0.5 --clearcoat "$strength" --clearcoat-roughness "$rc" --background 0,0,0
          --quiet)
    [ -f "$name-ref.exr" ] || "$IBL" render "${args[@]}" --mode reference --spp "$REF_SPP" \
      -o "$name-ref.exr"
    [ -f "$name-rt.exr" ] || "$IBL" render "${args[@]}" --spp 16 -o "$name-rt.exr"
    printf '%-8s %-10s %-10s %s\n' "$light" "$strength" "$rc" "$(figures "$name-rt.exr" "$name-ref.exr")"
  done
done
