#include "ibl/stats.hpp"

#include <cmath>
#include <limits>

#include "ibl/color.hpp"
#include "ibl/equirect.hpp"

namespace ibl {

ImageStats imageStats(const Image& img) {
  ImageStats s;
  s.invalid = countInvalidPixels(img);
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  glm::dvec3 sum(0.0);
  std::size_t finite[3] = {0, 0, 0};
  for (const auto& p : img.pixels)
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(p[c])) continue;
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
      sum[c] += p[c];
      ++finite[c];
    }
  for (int c = 0; c < 3; ++c) {
    if (finite[c] == 0) lo[c] = hi[c] = 0.0f;
    s.mean[c] = finite[c] ? sum[c] / static_cast<double>(finite[c]) : 0.0;
  }
  s.min = lo;
  s.max = hi;
  return s;
}

glm::dvec3 radiantIntegral(const Environment& env) {
  return env.isCube() ? integrateCube(env.cube, 0) : integrateEquirect(env.equirect);
}

glm::vec3 brightestDirection(const Environment& env) {
  float best = -1.0f;
  glm::vec3 dir(0.0f, 1.0f, 0.0f);
  if (env.isCube()) {
    const int n = env.cube.size();
    for (int f = 0; f < kFaceCount; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const float l = luminance(env.cube.levels[0][f].at(x, y));
          if (l > best) {
            best = l;
            dir = texelDirection(f, x, y, n);
          }
        }
  } else {
    const Image& img = env.equirect;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const float l = luminance(img.at(x, y));
        if (l > best) {
          best = l;
          dir =
              equirectToDirection((static_cast<float>(x) + 0.5f) / static_cast<float>(img.width),
                                  (static_cast<float>(y) + 0.5f) / static_cast<float>(img.height));
        }
      }
  }
  return dir;
}

}  // namespace ibl
