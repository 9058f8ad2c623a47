#pragma once
// Helpers of the containers' tests (KTX 1.1, DDS, Babylon.js's .env): the files are read back
// with parsers written from the specifications, not with the library's decoders.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "ibl/core/image.hpp"

namespace ibl::test {

// The little-endian 32-bit word at byte `at`.
inline std::uint32_t word(const std::vector<std::uint8_t>& b, std::size_t at) {
  return b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) |
         (static_cast<std::uint32_t>(b[at + 3]) << 24);
}

// A cube whose texels encode face, level and position (exact in half floats and within the
// 11-bit floats' precision).
inline std::vector<std::vector<Image>> testCube(int size, int levels) {
  std::vector<std::vector<Image>> cube(levels);
  for (int m = 0; m < levels; ++m)
    for (int f = 0; f < 6; ++f) {
      Image img(size >> m, size >> m);
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
          img.at(x, y) = glm::vec3(f + 1, m + 0.5f, 0.25f * static_cast<float>(x + 2 * y));
      cube[m].push_back(img);
    }
  return cube;
}

// The relative error of a decoded RGBD texel: against the brightest channel of the reference
// (8-bit gamma steps are relative to it), with a floor for black texels.
inline double rgbdError(glm::vec3 a, glm::vec3 ref) {
  const float scale = std::max({ref.x, ref.y, ref.z, 0.05f});
  return glm::length(a - ref) / scale;
}

}  // namespace ibl::test
