#include "ktx_shape.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/env/cubemap.hpp"

namespace ibl {

std::uint32_t checkKtxShape(std::string_view name, const KtxShape& shape,
                            const KtxFieldNames& fields) {
  const std::uint32_t width = shape.width, height = shape.height, faces = shape.faces;
  if (height == 0) fail(name, "1D textures are not supported");
  if (shape.depth != 0) fail(name, "3D textures are not supported");
  if (shape.layers != 0) fail(name, "texture arrays are not supported");
  if (faces != 1 && faces != 6) fail(name, fmt::format("{} {} is invalid", fields.faces, faces));
  if (faces == 6 && width != height) fail(name, "cube map faces are not square");
  checkImageSize(name, width, height);
  std::uint32_t levels = shape.levels;
  if (levels == 0) levels = 1;  // "generate mipmaps": we read the one stored level
  if (levels > static_cast<std::uint32_t>(fullMipCount(static_cast<int>(std::max(width, height)))))
    fail(name, fmt::format("{} {} is too large for {}x{}", fields.levels, levels, width, height));
  return levels;
}

void checkKtxLevelCount(std::string_view codec, std::size_t levelCount, int faceCount) {
  if (levelCount == 0 || (faceCount != 1 && faceCount != 6))
    fail(codec, "a texture needs at least one level and 1 or 6 faces");
}

void checkKtxLevel(std::string_view codec, const std::vector<Image>& faces, std::size_t level,
                   int faceCount, int width, int height) {
  if (faces.size() != static_cast<std::size_t>(faceCount))
    fail(codec, fmt::format("level {} has {} faces, expected {}", level, faces.size(), faceCount));
  const int w = std::max(1, width >> level), h = std::max(1, height >> level);
  for (const Image& f : faces)
    if (f.width != w || f.height != h)
      fail(codec, fmt::format("level {} is {}x{}, expected {}x{}", level, f.width, f.height, w, h));
}

}  // namespace ibl
