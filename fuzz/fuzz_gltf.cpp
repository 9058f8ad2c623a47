// libFuzzer target for the glTF loader: .gltf text and .glb containers, with Draco and
// EXT_meshopt_compression primitives and embedded images (fuzz/seeds/gltf). Each input is loaded
// as `ibl render` loads it and described as `ibl info` does. The loader may reject it with
// ibl::Error; anything else (a crash, a sanitizer report, another exception, a hang, an
// allocation past libFuzzer's -malloc_limit_mb, which scripts/fuzz.sh sets to 2048) is a bug.
// The loader's own limits are lowered below that, so that what they allow fits under it.
#include <cstddef>
#include <cstdint>
#include <span>

#include "ibl/core/error.hpp"
#include "ibl/render/gltf.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  ibl::GltfLoadOptions options;
  options.maxGeometryBytes = std::uint64_t{256} << 20;
  options.maxTextureBytes = std::uint64_t{256} << 20;
  // External buffers and images are looked for in a folder that does not exist.
  const std::string path = "/nonexistent-ibl-fuzz/fuzz.gltf";
  try {
    ibl::loadGltf(bytes, path, options);
  } catch (const ibl::Error&) {
  }
  try {
    ibl::describeGltf(bytes, path, options);
  } catch (const ibl::Error&) {
  }
  return 0;
}
