#!/usr/bin/env bash
# KHR_materials_transmission and KHR_materials_volume: the split sum against the path-traced
# reference (docs/materials.md, "Transmission and volume", "Measured"). A clear glass (base color
# 1) and a tinted one (0.9 0.7 0.5), each at roughness 0, 0.2 and 0.5, as a thin wall and as a
# solid sphere (thickness 2, the real-time paths' crossing; attenuation color 0.8 0.6 0.4 after
# 2), under two HDRIs (park, sunset) and one analytic light (a point light, no environment);
# prints `ibl compare`'s frame error and median 4 x 4 block error for each. Outputs already
# present are kept (delete OUT to start over). Environment: IBL (default build-dev/ibl), OUT
# (default out/transmission), SIZE (128x128), REF_SPP (1024).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-out/transmission}
source tools/measure_common.sh
printf '%-8s %-6s %-9s %-6s %10s %10s\n' light glass roughness body frame median
for light in park sunset point; do
  lightingFor "$light"
  for glass in clear tinted; do
    if [ "$glass" = clear ]; then color=(--base-color 1,1,1); else color=(--base-color 0.9,0.7,0.5); fi
    for roughness in 0 0.2 0.5; do
      for body in thin solid; do
        volume=()
        [ "$body" = solid ] && volume=(--thickness 2 --attenuation-distance 2
                                       --attenuation-color 0.8,0.6,0.4)
        name="$OUT/$light-$glass-$roughness-$body"
        args=(sphere "${lighting[@]}" --size "$SIZE" "${color[@]}" --metallic 0
              --roughness "$roughness" --transmission 1 "${volume[@]}" --background 0,0,0 --quiet)
        [ -f "$name-ref.exr" ] || "$IBL" render "${args[@]}" --mode reference --bounces 8 \
          --spp "$REF_SPP" -o "$name-ref.exr"
        [ -f "$name-rt.exr" ] || "$IBL" render "${args[@]}" --spp 16 -o "$name-rt.exr"
        printf '%-8s %-6s %-9s %-6s %s\n' "$light" "$glass" "$roughness" "$body" \
          "$(figures "$name-rt.exr" "$name-ref.exr")"
      done
    done
  done
done
# What the glass shows of the opaque surfaces behind it: data/scenes/glass.gltf (a solid ball of
# absorbing glass and a thin frosted pane before a striped wall, on a checkered floor) at SCENE_SIZE
# (default 320x240): the frame error and the median block error over the whole image and over the
# glass alone (a mask: the same scene with every material unlit, the glass white, the rest black).
SCENE_SIZE=${SCENE_SIZE:-320x240}
python3 - "$OUT/glass_mask.gltf" <<'PY'
import json, sys
doc = json.load(open("data/scenes/glass.gltf"))
for m in doc["materials"]:
    glass = "KHR_materials_transmission" in m.get("extensions", {})
    m["pbrMetallicRoughness"] = {"baseColorFactor": [1, 1, 1, 1] if glass else [0, 0, 0, 1]}
    m["extensions"] = {"KHR_materials_unlit": {}}
doc["extensionsUsed"] = ["KHR_materials_unlit"]
json.dump(doc, open(sys.argv[1], "w"))
PY
"$IBL" render "$OUT/glass_mask.gltf" --env none --size "$SCENE_SIZE" --spp 1 --quiet \
  -o "$OUT/glass_mask.png"
printf '\n%-8s %-6s %10s %10s\n' light pixels frame median
for light in park sunset; do
  name="$OUT/scene-$light"
  args=(data/scenes/glass.gltf --env "data/hdri/$light.exr" --size "$SCENE_SIZE" --quiet)
  [ -f "$name-ref.exr" ] || "$IBL" render "${args[@]}" --mode reference --bounces 8 \
    --spp "$REF_SPP" -o "$name-ref.exr"
  [ -f "$name-rt.exr" ] || "$IBL" render "${args[@]}" --spp 16 -o "$name-rt.exr"
  printf '%-8s %-6s %s\n' "$light" all "$(figures "$name-rt.exr" "$name-ref.exr")"
  printf '%-8s %-6s %s\n' "$light" glass \
    "$(figures "$name-rt.exr" "$name-ref.exr" --mask "$OUT/glass_mask.png")"
done
