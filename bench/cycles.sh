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
set -euo pipefail

IBL=${1:?usage: bench/cycles.sh IBL_BINARY [SPP]}
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

ibl_seconds() {  # from "rendered X (WxH, reference, N samples, T s, ...)"
  sed -n 's/^rendered .* samples, \([0-9.]*\) s, .*/\1/p' "$1.log" | tail -1
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
