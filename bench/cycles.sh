#!/usr/bin/env bash
# The reference renderer's efficiency (noise per second of compute) against Blender Cycles on
# the same scene: a white metal sphere (roughness 0.5, single scattering) under
# data/hdri/park.exr, 256x256, lit by the environment alone, both on the CPU with 2 threads.
#
#   bash bench/cycles.sh IBL_BINARY [SPP]        (SPP: 256 by default)
#
# Without `blender` on PATH (Debian: apt-get install blender) it says so and exits 0.
# Each renderer renders the scene twice (seeds 1 and 2); the noise of one render is measured
# from the difference of the two (bench/noise_stats.py, no converged image needed), and the
# efficiency is 1 / (relative noise^2 x render seconds). Render seconds: ibl's own report (the
# render after the bake: scene setup, sampling tables, path tracing) and Cycles' render call
# (sync, background importance map, path tracing), neither counting the process start, nor
# ibl's bake (printed apart as the process wall time).
# First, unless CHECK_ORIENTATION=0, it checks that the two environments are oriented alike:
# a mirror sphere (roughness 0) at 64x64 in both, with a rotated and a mirrored map in
# Cycles as controls, which must differ far more.
# Environment: SIZE (256x256), ROUGHNESS (0.5), THREADS (2), ENV_MAP (data/hdri/park.exr),
# OUT_DIR (a new /tmp directory), CPU_LOCK (a file: every render runs under `flock` on it, and
# its time is measured inside the lock).
#
#   bash bench/cycles.sh --scene room IBL_BINARY [SPP]     (or SCENE=room)
#
# The second scene: data/scenes/room.gltf (a 5 x 3 x 5 m room open toward +Z, Lambert + GGX
# materials) lit by the rect light of data/scenes/room_lights.json alone (2500 lm, 4500 K, 1.2 x
# 0.5 m under the ceiling, emitting down), `--env none`, seen by ibl's default framing of the
# room (--look-from 0,1.5,10.0556 --look-at 0,1.5,0, fov 40), path traced with BOUNCES (4)
# bounces, `--multiscatter off`, `--diffuse lambert`. The glTF's own KHR_lights_punctual spot
# and point are left out of a copy of it that both renderers load (ibl cannot leave them out,
# and its spot cone and range window have no exact Cycles equivalent). Cycles imports the glTF
# with the bundled importer (it needs NumPy: apt-get install python3-numpy) and converts the
# rect light (bench/cycles_scene.py: its units, color and orientation). The same table as the
# sphere's, over the room's pixels (Cycles gives the light's own pixels alpha 0: left out).
# Room environment: BOUNCES (4), DIFFUSE (lambert, or disney: ibl's renormalized Disney against
# Cycles' Principled diffuse, which differ), ROOM_GLTF, ROOM_LIGHTS, LOOK_FROM, LOOK_AT.
set -euo pipefail

SCENE=${SCENE:-sphere}
if [[ ${1:-} == --scene ]]; then
  SCENE=${2:?usage: bench/cycles.sh --scene sphere|room IBL_BINARY [SPP]}
  shift 2
fi
[[ $SCENE == sphere || $SCENE == room ]] || { echo "cycles.sh: unknown scene '$SCENE' (sphere, room)" >&2; exit 2; }
IBL=${1:?usage: bench/cycles.sh [--scene sphere|room] IBL_BINARY [SPP]}
SPP=${2:-256}
if ! command -v blender >/dev/null 2>&1; then
  echo "cycles.sh: blender is not on PATH (apt-get install blender); skipped"
  exit 0
fi
ROOT=$(cd "$(dirname "$0")/.." && pwd)
IBL=$(cd "$(dirname "$IBL")" && pwd)/$(basename "$IBL")
ENV_MAP=${ENV_MAP:-$ROOT/data/hdri/park.exr}
SIZE=${SIZE:-256x256}
ROUGHNESS=${ROUGHNESS:-0.5}
THREADS=${THREADS:-2}
OUT_DIR=${OUT_DIR:-$(mktemp -d /tmp/ibl-cycles.XXXXXX)}
mkdir -p "$OUT_DIR"
BLENDER=(blender -b --factory-startup)

# run LOG CMD...: runs CMD (under flock CPU_LOCK if set), its output in LOG, and prints its
# wall time in seconds, measured inside the lock.
run() {
  local log=$1
  shift
  local body='s=$(date +%s.%N); "$@" >"$LOG" 2>&1 || { cat "$LOG" >&2; exit 1; }; e=$(date +%s.%N); echo "$s $e" | awk "{printf \"%.3f\", \$2 - \$1}"'
  if [[ -n ${CPU_LOCK:-} ]]; then
    LOG=$log flock "$CPU_LOCK" bash -c "$body" bash "$@"
  else
    LOG=$log bash -c "$body" bash "$@"
  fi
}

ibl_render() {  # ibl_render SEED SPP SIZE ROUGHNESS OUT
  run "$5.log" "$IBL" --threads "$THREADS" render sphere --env "$ENV_MAP" --metallic 1 \
    --roughness "$4" --base-color 1,1,1 --multiscatter off --mode reference --size "$3" \
    --spp "$2" --tonemap none --background 0,0,0 --seed "$1" -o "$5"
}

cycles_render() {  # cycles_render SEED SPP SIZE ROUGHNESS OUT [extra options]
  local seed=$1 spp=$2 size=$3 rough=$4 out=$5
  shift 5
  run "$out.log" "${BLENDER[@]}" -P "$ROOT/bench/cycles_scene.py" -- --env "$ENV_MAP" \
    --size "$size" --spp "$spp" --seed "$seed" --roughness "$rough" --threads "$THREADS" \
    -o "$out" "$@"
}

ibl_seconds() {  # the shading's, from "rendered X (WxH, reference, N samples, W s in all, T s shading, ...)"
  sed -n 's/^rendered .* s in all, \([0-9.]*\) s shading, .*/\1/p' "$1.log" | tail -1
}
cycles_seconds() { sed -n 's/^cycles_render_seconds: //p' "$1.log" | tail -1; }
# Cycles' own clock at its first sample and at the end: the path tracing alone is the difference
cycles_sampling_seconds() {
  awk '/Time:/ { match($0, /Time:[0-9:.]+/); t = substr($0, RSTART + 5, RLENGTH - 5);
                 n = split(t, p, ":"); s = 0; for (i = 1; i <= n; ++i) s = 60 * s + p[i] }
       / Sample 0\// { t0 = s } / Finished/ { t1 = s } END { printf "%.2f", t1 - t0 }' "$1.log"
}

stats() { "${BLENDER[@]}" -P "$ROOT/bench/noise_stats.py" -- "$@" 2>&1 | sed -n '/^Blender quit/d;/^Read /d;/^Blender 3/d;/^$/d;p'; }

echo "== ibl: $IBL ($("$IBL" --version 2>&1 | head -1)); $(blender -b --version 2>/dev/null | head -1)"
echo "== $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); threads $THREADS; output in $OUT_DIR"

if [[ $SCENE == room ]]; then
  ROOM_GLTF=${ROOM_GLTF:-$ROOT/data/scenes/room.gltf}
  ROOM_LIGHTS=$(cd "$(dirname "${ROOM_LIGHTS:-$ROOT/data/scenes/room_lights.json}")" && pwd)/$(basename "${ROOM_LIGHTS:-room_lights.json}")
  BOUNCES=${BOUNCES:-4}
  DIFFUSE=${DIFFUSE:-lambert}
  # ibl's default camera for the room's bounds [-2.5, 2.5] x [0, 3] x [-2.5, 2.5]
  # (apps/scene_options.cpp): at the center, backed off along +Z by 1.1 * max(1.5, 2.5) /
  # tan(20 deg) + 2.5; given explicitly to both renderers.
  LOOK_FROM=${LOOK_FROM:-0,1.5,10.0556}
  LOOK_AT=${LOOK_AT:-0,1.5,0}
  case $DIFFUSE in
    lambert) CYCLES_DIFFUSE=lambert ;;
    disney) CYCLES_DIFFUSE=principled ;;
    *) echo "cycles.sh: DIFFUSE is lambert or disney, not '$DIFFUSE'" >&2; exit 2 ;;
  esac
  # The glTF without its KHR_lights_punctual lights, for both renderers.
  python3 - "$ROOM_GLTF" "$OUT_DIR/room_nolights.gltf" <<'PY'
import json, sys
g = json.load(open(sys.argv[1]))
drop = {i for i, n in enumerate(g.get("nodes", [])) if "KHR_lights_punctual" in n.get("extensions", {})}
for n in g.get("nodes", []):
    if set(n.get("children", [])) & drop:
        sys.exit("cycles.sh: a light node has a parent; not handled")
keep = [i for i in range(len(g.get("nodes", []))) if i not in drop]
new = {old: k for k, old in enumerate(keep)}
g["nodes"] = [g["nodes"][i] for i in keep]
for n in g["nodes"]:
    if "children" in n:
        n["children"] = [new[c] for c in n["children"]]
for sc in g.get("scenes", []):
    sc["nodes"] = [new[i] for i in sc["nodes"] if i in new]
g.get("extensions", {}).pop("KHR_lights_punctual", None)
if not g.get("extensions", True):
    del g["extensions"]
g["extensionsUsed"] = [e for e in g.get("extensionsUsed", []) if e != "KHR_lights_punctual"]
if not g["extensionsUsed"]:
    del g["extensionsUsed"]
json.dump(g, open(sys.argv[2], "w"))
print(f"== {sys.argv[1]}: {len(drop)} KHR_lights_punctual light node(s) left out")
PY
  ROOM=$OUT_DIR/room_nolights.gltf
  ibl_room_render() {  # ibl_room_render SEED SPP OUT
    run "$3.log" "$IBL" --threads "$THREADS" render "$ROOM" --lights "$ROOM_LIGHTS" --env none \
      --look-from "$LOOK_FROM" --look-at "$LOOK_AT" --diffuse "$DIFFUSE" --multiscatter off \
      --mode reference --size "$SIZE" --spp "$2" --bounces "$BOUNCES" --tonemap none \
      --seed "$1" -o "$3"
  }
  cycles_room_render() {  # cycles_room_render SEED SPP OUT
    run "$3.log" "${BLENDER[@]}" -P "$ROOT/bench/cycles_scene.py" -- --scene room --gltf "$ROOM" \
      --lights "$ROOM_LIGHTS" --look-from "$LOOK_FROM" --look-at "$LOOK_AT" \
      --diffuse "$CYCLES_DIFFUSE" --bounces "$BOUNCES" --size "$SIZE" --spp "$2" --seed "$1" \
      --threads "$THREADS" -o "$3"
  }
  echo "== room: $SIZE, $SPP spp, $BOUNCES bounces, diffuse $DIFFUSE (Cycles: $CYCLES_DIFFUSE), seeds 1 and 2"
  declare -a IW IS CW CS CT
  for seed in 1 2; do
    f=$OUT_DIR/room_ibl_${SPP}_s$seed.exr
    IW[$seed]=$(ibl_room_render "$seed" "$SPP" "$f")
    IS[$seed]=$(ibl_seconds "$f")
    g=$OUT_DIR/room_cycles_${SPP}_s$seed.exr
    CW[$seed]=$(cycles_room_render "$seed" "$SPP" "$g")
    CS[$seed]=$(cycles_seconds "$g")
    CT[$seed]=$(cycles_sampling_seconds "$g")
    echo "seed $seed: ibl ${IS[$seed]} s render (${IW[$seed]} s process);" \
      "cycles ${CS[$seed]} s render, of which ${CT[$seed]} s sampling" \
      "(${CW[$seed]} s process, Blender's start included)"
  done
  grep -h '^cycles_room_light' "$OUT_DIR/room_cycles_${SPP}_s1.exr.log" | sed 's/^/  /'
  stats noise --spp "$SPP" --region room \
    --ibl "$OUT_DIR/room_ibl_${SPP}_s1.exr" "$OUT_DIR/room_ibl_${SPP}_s2.exr" \
    --ibl-seconds "${IS[1]}" "${IS[2]}" \
    --blender "$OUT_DIR/room_cycles_${SPP}_s1.exr" "$OUT_DIR/room_cycles_${SPP}_s2.exr" \
    --blender-seconds "${CS[1]}" "${CS[2]}" --blender-sampling-seconds "${CT[1]}" "${CT[2]}"
  exit 0
fi

if [[ ${CHECK_ORIENTATION:-1} != 0 ]]; then
  echo "== orientation: mirror sphere (roughness 0), 64x64, 64 spp; Cycles against ibl"
  ibl_render 1 64 64x64 0 "$OUT_DIR/mirror_ibl.exr" >/dev/null
  cycles_render 1 64 64x64 0 "$OUT_DIR/mirror_cycles.exr" >/dev/null
  cycles_render 1 64 64x64 0 "$OUT_DIR/mirror_cycles_rot90.exr" --env-rotate-z 90 >/dev/null
  cycles_render 1 64 64x64 0 "$OUT_DIR/mirror_cycles_mirrored.exr" --env-mirror >/dev/null
  stats compare "$OUT_DIR/mirror_ibl.exr" "$OUT_DIR/mirror_cycles.exr" \
    "$OUT_DIR/mirror_cycles_rot90.exr" "$OUT_DIR/mirror_cycles_mirrored.exr"
fi

echo "== $SIZE, $SPP spp, roughness $ROUGHNESS, seeds 1 and 2"
declare -a IW IS CW CS CT
for seed in 1 2; do
  f=$OUT_DIR/ibl_${SPP}_s$seed.exr
  IW[$seed]=$(ibl_render "$seed" "$SPP" "$SIZE" "$ROUGHNESS" "$f")
  IS[$seed]=$(ibl_seconds "$f")
  g=$OUT_DIR/cycles_${SPP}_s$seed.exr
  CW[$seed]=$(cycles_render "$seed" "$SPP" "$SIZE" "$ROUGHNESS" "$g")
  CS[$seed]=$(cycles_seconds "$g")
  CT[$seed]=$(cycles_sampling_seconds "$g")
  echo "seed $seed: ibl ${IS[$seed]} s render (${IW[$seed]} s process, bake included);" \
    "cycles ${CS[$seed]} s render, of which ${CT[$seed]} s sampling" \
    "(${CW[$seed]} s process, Blender's start included)"
done
stats noise --spp "$SPP" \
  --ibl "$OUT_DIR/ibl_${SPP}_s1.exr" "$OUT_DIR/ibl_${SPP}_s2.exr" --ibl-seconds "${IS[1]}" "${IS[2]}" \
  --blender "$OUT_DIR/cycles_${SPP}_s1.exr" "$OUT_DIR/cycles_${SPP}_s2.exr" \
  --blender-seconds "${CS[1]}" "${CS[2]}" --blender-sampling-seconds "${CT[1]}" "${CT[2]}"
