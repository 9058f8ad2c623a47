# shellcheck shell=bash
# What bench/cycles_dielectric.sh and bench/cycles_transmission.sh share, read with `source` once
# NAME (the script's name) and IBL (the ibl binary) are set: without `blender` on PATH a line
# that says so and exit 0; ROOT, IBL made absolute, OUT (a new folder unless given), ENV_MAP
# (data/hdri/park.exr), SIZE (128x128), and `luminance FILE`.
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
if ! command -v blender >/dev/null 2>&1; then
  echo "$NAME: blender is not on PATH (apt-get install blender); skipped"
  exit 0
fi
IBL=$(cd "$(dirname "$IBL")" && pwd)/$(basename "$IBL")
OUT=${OUT:-$(mktemp -d "/tmp/ibl-${NAME%.sh}.XXXXXX")}
ENV_MAP=$ROOT/data/hdri/park.exr
SIZE=128x128
luminance() {  # the mean Rec. 709 luminance of an image, from `ibl info`
  "$IBL" info "$1" | awk '/^mean/ { printf "%.6f", 0.2126 * $2 + 0.7152 * $3 + 0.0722 * $4 }'
}
