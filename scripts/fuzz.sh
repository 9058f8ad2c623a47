#!/usr/bin/env bash
# Fuzzes every image reader and the glTF loader with libFuzzer (clang, ASan + UBSan) for a
# bounded time.
#   scripts/fuzz.sh [SECONDS_PER_READER]   (default 30)
# Starts from fuzz/seeds/<reader>; a crash is copied to tests/corpus/ (tests/corpus/gltf/ for the
# glTF loader), where the regression tests replay it forever, and the script fails. An allocation
# past the memory limit (4096 MB, 2048 MB for the glTF loader, whose hostile files must cost
# about their own size) is a crash.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-30}"
build=build-fuzz
CC=clang-14 CXX=clang++-14 cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DIBL_FUZZ=ON -DIBL_BUILD_TESTS=OFF -DIBL_BUILD_BENCH=OFF >/dev/null
ninja -C "$build" fuzz_hdr fuzz_exr fuzz_ldr fuzz_ktx2 fuzz_ktx1 fuzz_dds fuzz_env fuzz_gltf >/dev/null
status=0
for reader in hdr exr ldr ktx2 ktx1 dds env gltf; do
  work="fuzz/corpus-work/$reader"
  artifacts="fuzz/corpus-work/artifacts-$reader"
  limit=4096 corpus=tests/corpus
  if [ "$reader" = gltf ]; then limit=2048 corpus=tests/corpus/gltf; fi
  mkdir -p "$work" "$artifacts"
  echo "fuzz: $reader for ${seconds}s" >&2
  if ! "$build/fuzz/fuzz_$reader" "$work" "fuzz/seeds/$reader" -max_total_time="$seconds" \
      -timeout=10 -rss_limit_mb="$limit" -malloc_limit_mb="$limit" -print_final_stats=1 \
      -artifact_prefix="$artifacts/" >"fuzz/corpus-work/$reader.log" 2>&1; then
    status=1
    tail -n 30 "fuzz/corpus-work/$reader.log" >&2
    for crash in "$artifacts"/*; do
      [ -f "$crash" ] || continue
      dest="$corpus/fuzz-$reader-$(sha1sum "$crash" | cut -c1-12)"
      cp "$crash" "$dest"
      echo "fuzz: $reader crashed; input kept as $dest" >&2
    done
  fi
  grep -E "stat::number_of_executed_runs|cov:" "fuzz/corpus-work/$reader.log" | tail -n 2 >&2 || true
done
exit "$status"
