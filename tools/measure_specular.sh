#!/usr/bin/env bash
# KHR_materials_ior and KHR_materials_specular: the split sum against the path-traced reference
# (docs/materials.md, "Measured"). A dielectric sphere (base color 0.2, r = 0.3 and 0.7) sweeps
# the index of refraction at specular 1, then the specular factor and color at IOR 1.5, under
# two HDRIs (park, sunset) and one analytic light (a point light, no environment); prints
# `ibl compare`'s frame error and median 4 x 4 block error for each. Outputs already present are
# kept (delete OUT to start over).
# Environment: IBL (default build-dev/ibl), OUT (default out/specular), SIZE (128x128),
# REF_SPP (1024).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-out/specular}
source tools/measure_common.sh
printf '%-8s %-22s %5s %10s %10s\n' light material r frame median
for light in park sunset point; do
  lightingFor "$light"
  for material in "ior=1.33" "ior=1.5" "ior=2" "ior=2.42" "specular=0.5" "specular=0"; do
    key=${material%%=*} value=${material#*=}
    for r in 0.3 0.7; do
      name="$OUT/$light-$key$value-r$r"
      args=(sphere "${lighting[@]}" --size "$SIZE" --base-color 0.2,0.2,0.2 --roughness "$r" --background 0,0,0
            "--$key" "$value" --quiet)
      [ -f "$name-ref.exr" ] || "$IBL" render "${args[@]}" --mode reference --spp "$REF_SPP" \
        -o "$name-ref.exr"
      [ -f "$name-rt.exr" ] || "$IBL" render "${args[@]}" --spp 16 -o "$name-rt.exr"
      printf '%-8s %-22s %5s %s\n' "$light" "$material" "$r" "$(figures "$name-rt.exr" "$name-ref.exr")"
    done
  done
done
