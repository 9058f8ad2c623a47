#include "ibl/render/bloom.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "ibl/core/parallel.hpp"
#include "ibl/shared/bloom.h"

namespace ibl {

namespace {

// Half the size (rounded up), filtered by the separable tent (1, 3, 3, 1) / 8 over the 4 x 4
// texels around each 2 x 2 block (edges clamped): the mean and, unlike a box, the centroid of
// the light are kept, so that the coarse scales stay centered on what blooms.
Image halve(const Image& source) {
  Image half((source.width + 1) / 2, (source.height + 1) / 2);
  parallelFor(0, half.height, [&](int y) {
    for (int x = 0; x < half.width; ++x) {
      glm::vec3 sum(0.0f);
      for (int j = 0; j < 4; ++j) {
        const int sy = std::clamp(2 * y - 1 + j, 0, source.height - 1);
        for (int i = 0; i < 4; ++i) {
          const int sx = std::clamp(2 * x - 1 + i, 0, source.width - 1);
          sum += (shared::bloomTap(i) * shared::bloomTap(j)) * source.at(sx, sy);
        }
      }
      half.at(x, y) = sum;
    }
  });
  return half;
}

// `source` brought to width x height (about twice its size) bilinearly, edges clamped, added to
// `base` (null: to nothing).
Image doubleOnto(const Image& source, int width, int height, const Image* base) {
  Image out(width, height);
  parallelFor(0, height, [&](int y) {
    const float sy = shared::bloomDoublingCoordinate(y, source.height);
    const int y0 = static_cast<int>(sy), y1 = std::min(y0 + 1, source.height - 1);
    const float fy = sy - static_cast<float>(y0);
    for (int x = 0; x < width; ++x) {
      const float sx = shared::bloomDoublingCoordinate(x, source.width);
      const int x0 = static_cast<int>(sx), x1 = std::min(x0 + 1, source.width - 1);
      const float fx = sx - static_cast<float>(x0);
      const glm::vec3 top = glm::mix(source.at(x0, y0), source.at(x1, y0), fx);
      const glm::vec3 bottom = glm::mix(source.at(x0, y1), source.at(x1, y1), fx);
      out.at(x, y) = glm::mix(top, bottom, fy) + (base ? base->at(x, y) : glm::vec3(0.0f));
    }
  });
  return out;
}

glm::dvec3 sumOf(const Image& image) {
  glm::dvec3 sum(0.0);
  for (const glm::vec3& p : image.pixels) sum += glm::dvec3(p);
  return sum;
}

}  // namespace

int bloomLevels(int width, int height) {
  return shared::bloomLevelCount(width, height);
}

Image applyBloom(const Image& linear, float ev100, float compensation) {
  const int levels = bloomLevels(linear.width, linear.height);
  if (levels == 0) return linear;
  const float threshold = shared::bloomThreshold(ev100, compensation);
  Image excess(linear.width, linear.height);
  for (std::size_t i = 0; i < linear.pixels.size(); ++i) {
    // A pixel that is not finite radiance stays as it is (spread, it would poison the image).
    const glm::vec3 c = linear.pixels[i];
    const bool radiance = std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) &&
                          c.x >= 0.0f && c.y >= 0.0f && c.z >= 0.0f;
    if (radiance) excess.pixels[i] = shared::bloomExcess(c, threshold);
  }
  const glm::dvec3 total = sumOf(excess);
  if (total == glm::dvec3(0.0)) return linear;
  // The pyramid: pyramid[k - 1] is the excess filtered to 1 / 2^k of the size, k = 1..levels.
  std::vector<Image> pyramid;
  pyramid.push_back(halve(excess));
  for (int k = 2; k <= levels; ++k) pyramid.push_back(halve(pyramid.back()));
  // Each scale alike: from the coarsest, doubled and added to the next finer, down to level 1,
  // then doubled to the image's size.
  Image sum = pyramid.back();
  for (int k = levels - 1; k >= 1; --k) {
    const Image& finer = pyramid[static_cast<std::size_t>(k - 1)];
    sum = doubleOnto(sum, finer.width, finer.height, &finer);
  }
  const Image spread = doubleOnto(sum, linear.width, linear.height, nullptr);
  // Normalized: the spread light's total is the excess's (what the edges and the odd sizes' last
  // rows and columns gain or lose goes back to every pixel in proportion).
  const glm::dvec3 spreadTotal = sumOf(spread);
  glm::vec3 scale(0.0f);
  for (int c = 0; c < 3; ++c)
    scale[c] = spreadTotal[c] > 0.0 ? static_cast<float>(total[c] / spreadTotal[c]) : 0.0f;
  Image out(linear.width, linear.height);
  for (std::size_t i = 0; i < out.pixels.size(); ++i)
    out.pixels[i] = linear.pixels[i] - excess.pixels[i] + spread.pixels[i] * scale;
  return out;
}

}  // namespace ibl
