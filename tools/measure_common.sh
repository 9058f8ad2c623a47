#!/usr/bin/env bash
# What the material measurements share (sourced by tools/measure_specular.sh and
# measure_clearcoat.sh): the defaults of IBL, SIZE and REF_SPP, OUT created, a point light's file
# ($OUT/point.json) and `figures IMAGE REFERENCE [COMPARE OPTIONS]`, which prints `ibl compare`'s frame error and
# median 4 x 4 block error, and `lightingFor LIGHT`, which sets the array `lighting` to the
# options of park, sunset (HDRIs) or point (the point light alone).
IBL=${IBL:-build-dev/ibl}
SIZE=${SIZE:-128x128}
REF_SPP=${REF_SPP:-1024}
mkdir -p "$OUT"
cat > "$OUT/point.json" <<'JSON'
{"lights": [{"type": "point", "position": [2, 3, 4], "intensity": 600, "unit": "cd"}]}
JSON
figures() {
  "$IBL" -q compare "$1" "$2" "${@:3}" --json | python3 -c '
import json, sys; f = json.load(sys.stdin)["frame"]
print("".join(f"{100 * f[k]:8.2f} %" for k in ("frame_error", "median_block_error")))'
}
lightingFor() {
  case $1 in
    point) lighting=(--env none --lights "$OUT/point.json") ;;
    *) lighting=(--env "data/hdri/$1.exr") ;;
  esac
}
