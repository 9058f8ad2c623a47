// libFuzzer target for one image reader, chosen at compile time by IBL_FUZZ_FORMAT
// (hdr, exr, ldr, ktx2, ktx1, dds, env, any). A reader may reject its input with ibl::Error;
// anything else (a crash, a sanitizer report, another exception, a hang) is a bug.
#include <cstddef>
#include <cstdint>
#include <span>

#include "ibl/core/error.hpp"
#include "ibl/io/babylon_env.hpp"
#include "ibl/io/dds.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/ktx1.hpp"
#include "ibl/io/ktx2.hpp"

#define IBL_FUZZ_hdr 1
#define IBL_FUZZ_exr 2
#define IBL_FUZZ_ldr 3
#define IBL_FUZZ_ktx2 4
#define IBL_FUZZ_any 5
#define IBL_FUZZ_ktx1 6
#define IBL_FUZZ_dds 7
#define IBL_FUZZ_env 8
#define IBL_FUZZ_SELECT(f) IBL_FUZZ_##f
#define IBL_FUZZ_ID(f) IBL_FUZZ_SELECT(f)

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  try {
#if IBL_FUZZ_ID(IBL_FUZZ_FORMAT) == IBL_FUZZ_hdr
    ibl::decodeHdr(bytes, "fuzz.hdr");
#elif IBL_FUZZ_ID(IBL_FUZZ_FORMAT) == IBL_FUZZ_exr
    ibl::decodeExr(bytes, "fuzz.exr");
#elif IBL_FUZZ_ID(IBL_FUZZ_FORMAT) == IBL_FUZZ_ldr
    ibl::decodeLdr(bytes, "fuzz.png");
#elif IBL_FUZZ_ID(IBL_FUZZ_FORMAT) == IBL_FUZZ_ktx2
    ibl::decodeKtx2(bytes, "fuzz.ktx2");
#elif IBL_FUZZ_ID(IBL_FUZZ_FORMAT) == IBL_FUZZ_ktx1
    ibl::decodeKtx1(bytes, "fuzz.ktx");
#elif IBL_FUZZ_ID(IBL_FUZZ_FORMAT) == IBL_FUZZ_dds
    ibl::decodeDds(bytes, "fuzz.dds");
#elif IBL_FUZZ_ID(IBL_FUZZ_FORMAT) == IBL_FUZZ_env
    ibl::decodeBabylonEnv(bytes, "fuzz.env");
#else
    ibl::decodeImageFile(bytes, "fuzz");
#endif
  } catch (const ibl::Error&) {
  }
  return 0;
}
