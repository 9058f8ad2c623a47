#!/usr/bin/env bash
# Builds the release tree and prints every benchmark figure: I/O and conversion, the default
# bake stage by stage, and the accuracy report. Usage: bash bench/run.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
ninja -C build ibl_bench_io ibl_bench_bake ibl_bench_render ibl_bench_gpu ibl_accuracy ibl_roundtrip ibl_process ibl_memory ibl_lights ibl_shadows >/dev/null
echo "== machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "== I/O and conversion (2048x1024 EXR -> 256^2 cube with mips -> KTX2)"
./build/bench/ibl_bench_io --benchmark_min_time=1
echo "== default bake (2048x1024 HDR -> 256^2 specular chain, 32^2 irradiance, SH9, 128^2 DFG)"
./build/bench/ibl_bench_bake --benchmark_min_time=1
echo "== rendering (512^2 sphere grid, split sum, 4 spp; reference throughput)"
./build/bench/ibl_bench_render --benchmark_min_time=1
echo "== GPU stages and the viewer's frame (Vulkan; the software device without a GPU)"
./build/bench/ibl_bench_gpu --benchmark_min_time=1
echo "== accuracy"
./build/bench/ibl_accuracy
echo "== resampling: sharpness and power of an equirect -> cube -> equirect round trip"
./build/bench/ibl_roundtrip
echo "== the default bake of a 1024x512 HDR as a whole process, stage by stage"
./build/bench/ibl_process
echo "== peak memory of \`ibl render\` on a large glTF (4.9 M triangles, five 2048^2 textures)"
./build/bench/ibl_memory
echo "== analytic lights: each real-time approximation against the reference, and the CPU cost"
./build/bench/ibl_lights 256
echo "== shadows: shadow maps and ray-traced visibility against the reference"
./build/bench/ibl_shadows 256
