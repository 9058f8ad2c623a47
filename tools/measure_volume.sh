#!/usr/bin/env bash
# The irradiance volume measured against the path-traced reference on the interiors of
# tools/make_interior_scenes.py (docs/probes.md, "Measured against the reference"): renders each
# room's reference (6 bounces), then the split sum with the distant environment alone, a 3 x 2 x 3
# probe grid, volumes at 1, 0.5 and 0.25 m, volume + probes, volume + probes + SSR + SSAO, and
# prints `ibl compare`'s frame error, median 4 x 4 block error and share of pixels off by 2x for
# each, the light leaked into the closed room of two_rooms.gltf, and the volumes' bake time per
# probe and atlas sizes. Outputs already present are kept (delete OUT to start over).
# Usage: tools/measure_volume.sh [refs|all]   (refs: the references alone)
# Environment: IBL (default build-dev/ibl), IBL_REF (the binary for the references, default IBL),
# OUT (default out/volume), SIZE (128x96), REF_SPP (4096), THREADS (2).
set -euo pipefail
cd "$(dirname "$0")/.."
IBL=${IBL:-build-dev/ibl}
IBL_REF=${IBL_REF:-$IBL}
OUT=${OUT:-out/volume}
SIZE=${SIZE:-128x96}
REF_SPP=${REF_SPP:-4096}
THREADS=${THREADS:-2}
phase=${1:-all}
mkdir -p "$OUT"
S=data/scenes
# A sun through the opening: high in the south for the skylight (its patch falls on the floor
# and the back wall), lower for the window in the south wall (z = +2, behind the camera).
SKY_HIGH="sky:elevation=65,azimuth=180"
SKY_LOW="sky:elevation=30,azimuth=180"
SKY_OPEN="sky:elevation=35,azimuth=135"
ROOM_BOUNDS="-2,0,-2,2,3,2"
TWO_BOUNDS="-4.05,0,-2,4.05,3,2"
OPEN_BOUNDS="-6,0,-6,6,3,6"
cam() {  # the camera of a view: CENTER_X (a room's center), or "open"
  if [ "$1" = open ]; then echo "--look-from 0,2.5,7 --look-at 0,0.6,0 --fov 50"
  else echo "--look-from $1,1.6,1.8 --look-at $1,0.8,-2 --fov 60"; fi
}
# view name -> scene, environment, camera, volume bounds
declare -A SCENE=([skylight]=skylight_room [window]=window_room [lit]=two_rooms
                  [dark]=two_rooms [open]=open_scene)
declare -A ENV=([skylight]=$SKY_HIGH [window]=$SKY_LOW [lit]=$SKY_LOW [dark]=$SKY_LOW
                [open]=$SKY_OPEN)
declare -A CAM=([skylight]="$(cam 0)" [window]="$(cam 0)" [lit]="$(cam -2.05)"
                [dark]="$(cam 2.05)" [open]="$(cam open)")
declare -A BOUNDS=([skylight]=$ROOM_BOUNDS [window]=$ROOM_BOUNDS [lit]=$TWO_BOUNDS
                   [dark]=$TWO_BOUNDS [open]=$OPEN_BOUNDS)
# The probe grids (3 x 2 x 3 in each room; 6 x 2 x 3 over the two rooms).
declare -A GRID=([skylight]=3,2,3 [window]=3,2,3 [lit]=6,2,3 [dark]=6,2,3 [open]=3,2,3)

once() {  # once FILE COMMAND...: runs COMMAND unless FILE exists, timing it into FILE.time
  local file=$1; shift
  [ -e "$file" ] && return 0
  mkdir -p "$(dirname "$file")"
  local t0=$SECONDS
  "$@" > "$file.log" 2>&1 || { echo "failed: $* (see $file.log)" >&2; tail -3 "$file.log" >&2; return 0; }
  echo $((SECONDS - t0)) > "$file.time"
}
render() {  # render VIEW OUTPUT [OPTIONS...]: the split sum (or anything with --mode reference)
  local v=$1 out=$2; shift 2
  once "$out" "$IBL" --threads "$THREADS" -q render "$S/${SCENE[$v]}.gltf" --env "${ENV[$v]}" \
    ${CAM[$v]} --size "$SIZE" --background 0,0,0 -o "$out" "$@"
}
reference() {  # reference VIEW OUTPUT SPP SEED
  local v=$1 out=$2 spp=$3 seed=$4
  once "$out" "$IBL_REF" --threads "$THREADS" -q render "$S/${SCENE[$v]}.gltf" --env "${ENV[$v]}" \
    ${CAM[$v]} --size "$SIZE" --background 0,0,0 --mode reference --bounces 6 --spp "$spp" \
    --seed "$seed" -o "$out"
}

# --- the references (6 bounces); the skylight and window rooms' again with another seed at
# half and a quarter of the samples, to measure the reference's own noise
for v in skylight window lit open; do reference $v "$OUT/$v/ref.exr" "$REF_SPP" 1; done
reference skylight "$OUT/skylight/ref_seed2.exr" $((REF_SPP / 2)) 2
reference window "$OUT/window/ref_seed2_$((REF_SPP / 4)).exr" $((REF_SPP / 4)) 2
reference dark "$OUT/dark/ref.exr" 64 1  # a closed room: black
[ "$phase" = refs ] && exit 0

# --- the captures, per scene: the probe grid and the volumes (--volume-size, --spp and the
# bounces as the probes'; 0.25 m with a 16-texel map)
probe() {  # probe VIEW DIR OPTIONS...
  local v=$1 dir=$2; shift 2
  once "$dir" "$IBL" --threads "$THREADS" -q probe "$S/${SCENE[$v]}.gltf" --env "${ENV[$v]}" \
    --bounds "${BOUNDS[$v]}" --bounces 6 -o "$dir" "$@"
}
declare -A COUNTS_1=([skylight]=4,3,4 [window]=4,3,4 [lit]=8,3,4 [open]=12,3,12)
declare -A COUNTS_05=([skylight]=8,6,8 [window]=8,6,8 [lit]=16,6,8)
declare -A COUNTS_025=([skylight]=16,12,16 [window]=16,12,16 [lit]=32,12,16)
for v in skylight window lit open; do
  c=$OUT/${SCENE[$v]}
  probe $v "$c/grid" --grid "${GRID[$v]}" --size 32 --spp 64
  probe $v "$c/vol_1" --volume "${COUNTS_1[$v]}" --volume-size 32 --spp 32
  [ -n "${COUNTS_05[$v]:-}" ] && probe $v "$c/vol_0.5" --volume "${COUNTS_05[$v]}" --volume-size 32 --spp 32
  [ -n "${COUNTS_025[$v]:-}" ] && probe $v "$c/vol_0.25" --volume "${COUNTS_025[$v]}" --volume-size 16 --spp 32
done

# --- the split sum's renders (screen-space AO and reflections off unless named)
split() {  # split VIEW NAME OPTIONS...
  local v=$1 name=$2; shift 2
  render $v "$OUT/$v/$name.exr" "$@"
}
off="--ssao off --ssr off"
for v in skylight window lit open dark; do
  c=$OUT/${SCENE[$v]}
  best=$c/vol_0.5; [ -d "$best" ] || best=$c/vol_1
  split $v distant $off
  split $v probes $off --probes "$c/grid"
  split $v vol_1 $off --volume "$c/vol_1"
  [ -d "$c/vol_0.5" ] && split $v vol_0.5 $off --volume "$c/vol_0.5"
  [ -d "$c/vol_0.25" ] && split $v vol_0.25 $off --volume "$c/vol_0.25"
  split $v vol+probes $off --volume "$best" --probes "$c/grid"
  split $v vol+probes+ssr+ssao --ssao on --ssr on --volume "$best" --probes "$c/grid"
done

# --- the table
figures() {  # figures IMAGE REFERENCE: frame error, median block error, off by 2x
  "$IBL" -q compare "$1" "$2" --json | python3 -c '
import json, sys; f = json.load(sys.stdin)["frame"]
print("".join(f"{100 * f[k]:8.1f} %" for k in ("frame_error", "median_block_error", "off_by_2x")))'
}
# The mean luminance of a whole image (`ibl info` reads a 4:3 image as a cube cross and counts
# its faces alone): from the frame error against a constant K = 2^20 above every pixel,
# sum (K - L) / (N K) = 1 - mean L / K. The constant is written as a flat Radiance HDR file.
python3 - "$OUT/constant.hdr" "${SIZE%x*}" "${SIZE#*x}" <<'PY'
import sys
path, w, h = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
with open(path, "wb") as f:  # RGBE (128, 128, 128, 149) = 0.5 * 2^21 = 2^20, flat scanlines
    f.write(f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {h} +X {w}\n".encode())
    f.write(bytes([128, 128, 128, 149]) * (w * h))
PY
mean_luminance() {  # the mean of the Rec.709 luminance of an image
  "$IBL" -q compare "$1" "$OUT/constant.hdr" --json | python3 -c '
import json, sys; f = json.load(sys.stdin)["frame"]["frame_error"]; print(f"{2**20 * (1 - f):.4g}")'
}
echo "reference: $SIZE, 6 bounces, $REF_SPP spp; its noise (seed 2 against seed 1):"
echo "  skylight ref_seed2 ($((REF_SPP / 2)) spp) vs ref: $(figures "$OUT/skylight/ref_seed2.exr" "$OUT/skylight/ref.exr")"
echo "  window ref_seed2 ($((REF_SPP / 4)) spp) vs ref: $(figures "$OUT/window/ref_seed2_$((REF_SPP / 4)).exr" "$OUT/window/ref.exr")"
printf "%-9s %-22s %9s %9s %9s\n" view configuration "frame" "block" "off 2x"
for v in skylight window lit open; do
  for name in distant probes vol_1 vol_0.5 vol_0.25 vol+probes vol+probes+ssr+ssao; do
    [ -e "$OUT/$v/$name.exr" ] || continue
    printf "%-9s %-22s %s\n" $v $name "$(figures "$OUT/$v/$name.exr" "$OUT/$v/ref.exr")"
  done
done
echo "leak into the closed room of two_rooms (mean luminance, cd/m^2; the lit room's reference: $(mean_luminance "$OUT/lit/ref.exr")):"
for name in ref distant probes vol_1 vol_0.5 vol_0.25 vol+probes vol+probes+ssr+ssao; do
  [ -e "$OUT/dark/$name.exr" ] && printf "  %-22s %s\n" $name "$(mean_luminance "$OUT/dark/$name.exr")"
done
echo "volumes: probes, bake time per probe, atlases (irradiance, distance):"
for d in "$OUT"/*/vol_*/; do
  python3 - "$d" <<'PY'
import json, os, sys
d = sys.argv[1]; m = json.load(open(os.path.join(d, "volume.json")))["irradiance_volume"]
nx, ny, nz = m["counts"]; n = nx * ny * nz
off = sum(1 for p in m["probes"] if not p["on"])
ms = m["capture"]["milliseconds"]
def atlas(t):  # RGBA32F texels of an atlas of tiles of t + 2 texels a side
    return f"{nx * ny * (t + 2)}x{nz * (t + 2)} = {nx * ny * nz * (t + 2) ** 2 * 16 / 2**20:.2f} MiB"
print(f"  {d}: {n} probes ({off} off), size {m['capture_size']}, spp {m['capture']['spp']}: "
      f"{ms / n:.0f} ms/probe; irradiance {atlas(m['irradiance']['texels'])}, "
      f"distance {atlas(m['distance']['texels'])}")
PY
done
# --- PNGs to look at: every image of a view at one exposure (its reference's mean luminance at
# 0.18 of white), 4x larger through the viewer of your choice
for v in skylight window lit open dark; do
  m=$(mean_luminance "$OUT/$v/ref.exr"); [ "$v" = dark ] && m=$(mean_luminance "$OUT/lit/ref.exr")
  ev=$(python3 -c "import math; print(round(math.log2(0.18 / $m), 2))")
  for f in "$OUT/$v"/*.exr; do
    once "${f%.exr}.png" "$IBL" -q convert "$f" -o "${f%.exr}.png" --exposure "$ev" \
      --input-layout equirect --layout equirect
  done
done
