#!/usr/bin/env bash
# Sets up the machine and runs every check CI runs:
#   1. release build with warnings as errors, and the whole test suite (with the installed tree,
#      the example program against it, the Debian packages, man pages, completions and the
#      Python module's unittest suite);
#   2. the engine targets rendered by Filament, Babylon.js, three.js and the glTF Sample Viewer in
#      headless Chromium against `ibl render` (scripts/engines.sh, docs/targets.md);
#   3. probe grids and batch bakes as Slurm array jobs on a cluster started for the test
#      (scripts/cluster.sh, docs/cluster.md; as root);
#   4. clang-format check;
#   5. libFuzzer on every reader for a bounded time (IBL_FUZZ_SECONDS each, default 4);
#   6. the test suite again under AddressSanitizer + UndefinedBehaviorSanitizer;
#   7. the test suite again under ThreadSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="$(nproc)"
# Each phase's start, in seconds since the script began (the whole script must stay under 50
# minutes on CI's 2 cores).
phase() { echo "== $1 (at ${SECONDS} s)" >&2; }

bash scripts/setup.sh

phase "release build and tests"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DIBL_WERROR=ON >/dev/null
ninja -C build
ctest --test-dir build --output-on-failure -j "$jobs"

phase "engines in the browser"
bash scripts/engines.sh

phase "Slurm array jobs"
# Its daemons run as root.
if [ "$(id -u)" -eq 0 ]; then bash scripts/cluster.sh; else sudo -E env PATH="$PATH" bash scripts/cluster.sh; fi

phase "clang-format"
git ls-files '*.cpp' '*.hpp' '*.h' | xargs clang-format --dry-run --Werror

phase "fuzzing the readers"
bash scripts/fuzz.sh "${IBL_FUZZ_SECONDS:-4}"

phase "AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
# Left out here, run in the release phase: the tests tests/asan_excluded.txt lists, with why.
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DIBL_SANITIZE=ON \
  -DIBL_WERROR=ON -DIBL_BUILD_BENCH=OFF >/dev/null
ninja -C build-asan ibl_cli ibl_tests ibl_gpu_tests
mapfile -t excluded < <(sed -e 's/#.*//' -e 's/[[:space:]]*$//' -e '/^$/d' tests/asan_excluded.txt)
# A name the suite no longer has would leave out nothing: the list must stay true.
listed="$(ctest --test-dir build-asan -N | sed -n 's/^ *Test *#[0-9]*: //p')"
for name in "${excluded[@]}"; do
  grep -qxF "$name" <<<"$listed" || { echo "tests/asan_excluded.txt: no test $name" >&2; exit 1; }
done
ctest --test-dir build-asan --output-on-failure -j "$jobs" \
  -E "^($(printf '%s\n' "${excluded[@]}" | sed 's/\./\\./g' | paste -sd '|'))\$"

phase "ThreadSanitizer build and tests"
# The suites that run the library's own parallel code (oneTBB, through include/ibl/core/
# parallel.hpp, which annotates fork and join); a ThreadSanitizer build compiles only their files
# (tests/CMakeLists.txt). Left out: the GPU tests (the Vulkan driver's threads) and the
# command-line tests (the same code through the executable), and seven long measurements whose
# parallel loops other tests of their suites run. Mutex reports are
# off: OpenEXR locks inside its library and unlocks in header code inlined into ours.
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DIBL_TSAN=ON \
  -DIBL_WERROR=ON -DIBL_BUILD_BENCH=OFF >/dev/null
ninja -C build-tsan ibl_tests
TSAN_OPTIONS="halt_on_error=1 report_mutex_bugs=0 suppressions=$PWD/tests/tsan.supp" \
  ctest --test-dir build-tsan --output-on-failure -j "$jobs" \
  -R '^(CubeMap|Equirect|Resample|Sh|Sampling|Brdf|Dfg|Prefilter|Bake|Render|ShadingRules|Camera|Environment|PixelDamage|Sky|SunExtraction|LightClusters|AmbientOcclusion|Bloom|ScreenSpaceReflections)\.' \
  -E '^(Sky\.AgreesWithThePathTracedReference|Prefilter\.RingsMatchDirectQuadratureForSharpLobes|Resample\.SunKeepsItsEnergyFrom4KTo64|SunExtraction\.RenderWithoutTheSunPlusTheSunLightMatchesTheOriginal|Prefilter\.CoarseLevelsComputedSmallerAndInterpolated|Prefilter\.LevelsAgainstAnIndependentReference|Sky\.PanoramaMatchesTheDirectIntegration)$'
phase "done"
