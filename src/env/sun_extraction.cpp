#include "ibl/env/sun_extraction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibl/env/equirect.hpp"
#include "ibl/math/color.hpp"

namespace ibl {

namespace {

struct Pixel {
  int x, y;
};

// Pixels of the panorama around (x, y): the 8 neighbours, wrapping in x, clamped in y.
template <typename Visit>
void forNeighbours(int x, int y, int width, int height, const Visit& visit) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if ((dx == 0 && dy == 0) || y + dy < 0 || y + dy >= height) continue;
      visit((x + dx + width) % width, y + dy);
    }
}

// The pixels connected to `seed` whose luminance exceeds `threshold`.
std::vector<Pixel> connectedAbove(const std::vector<float>& lum, int width, int height, Pixel seed,
                                  float threshold, std::vector<char>& mark) {
  std::fill(mark.begin(), mark.end(), 0);
  std::vector<Pixel> region{seed}, stack{seed};
  mark[static_cast<std::size_t>(seed.y) * width + seed.x] = 1;
  while (!stack.empty()) {
    const Pixel p = stack.back();
    stack.pop_back();
    forNeighbours(p.x, p.y, width, height, [&](int x, int y) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      if (mark[i] || lum[i] <= threshold) return;
      mark[i] = 1;
      region.push_back({x, y});
      stack.push_back({x, y});
    });
  }
  return region;
}

}  // namespace

std::optional<ExtractedSun> extractSun(Image& panorama, float minimumRatio) {
  const int w = panorama.width, h = panorama.height;
  if (w < 4 || h < 2) return std::nullopt;
  const auto direction = [&](int x, int y) {
    return equirectToDirection((static_cast<float>(x) + 0.5f) / static_cast<float>(w),
                               (static_cast<float>(y) + 0.5f) / static_cast<float>(h));
  };
  std::vector<float> lum(panorama.pixels.size());
  std::size_t peak = 0;
  for (std::size_t i = 0; i < lum.size(); ++i) {
    lum[i] = luminance(panorama.pixels[i]);
    if (lum[i] > lum[peak]) peak = i;
  }
  if (!(lum[peak] > 0.0f)) return std::nullopt;
  const Pixel seed{static_cast<int>(peak % w), static_cast<int>(peak / w)};
  const glm::vec3 seedDir = direction(seed.x, seed.y);
  std::vector<char> mark(lum.size());
  const auto angularRadius = [&](const std::vector<Pixel>& region) {
    float cosMax = 1.0f;
    for (const Pixel& p : region) cosMax = std::min(cosMax, glm::dot(direction(p.x, p.y), seedDir));
    return std::acos(std::clamp(cosMax, -1.0f, 1.0f)) +
           std::numbers::pi_v<float> / static_cast<float>(h);  // + a pixel
  };

  // The core (above 5 % of the peak) gives the source's size, a ring around it the sky's level.
  const float coreRadius = angularRadius(connectedAbove(lum, w, h, seed, 0.05f * lum[peak], mark));
  std::vector<float> ring;
  const float cosInner = std::cos(std::min(4.0f * coreRadius, 1.2f));
  const float cosOuter = std::cos(std::min(8.0f * coreRadius, 1.5f));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float c = glm::dot(direction(x, y), seedDir);
      if (c <= cosInner && c >= cosOuter) ring.push_back(lum[static_cast<std::size_t>(y) * w + x]);
    }
  if (ring.empty()) return std::nullopt;
  std::nth_element(ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(ring.size() / 2),
                   ring.end());
  const float background = std::max(ring[ring.size() / 2], 1e-30f);
  const float ratio = lum[peak] / background;
  if (!(ratio >= minimumRatio)) return std::nullopt;

  std::vector<Pixel> region =
      connectedAbove(lum, w, h, seed, std::sqrt(lum[peak] * background), mark);
  if (angularRadius(region) > glm::radians(10.0f)) return std::nullopt;
  // One pixel more all round: the rim's partly covered pixels.
  for (std::size_t k = 0, n = region.size(); k < n; ++k)
    forNeighbours(region[k].x, region[k].y, w, h, [&](int x, int y) {
      char& m = mark[static_cast<std::size_t>(y) * w + x];
      if (!m) {
        m = 1;
        region.push_back({x, y});
      }
    });
  std::vector<Pixel> border;
  for (const Pixel& p : region)
    forNeighbours(p.x, p.y, w, h, [&](int x, int y) {
      char& m = mark[static_cast<std::size_t>(y) * w + x];
      if (!m) {
        m = 2;
        border.push_back({x, y});
      }
    });
  if (border.empty()) return std::nullopt;

  // The fill: inverse-square-distance weights over the border (a membrane over the hole).
  std::vector<glm::vec3> fill(region.size());
  for (std::size_t k = 0; k < region.size(); ++k) {
    const glm::vec3 d = direction(region[k].x, region[k].y);
    glm::dvec3 sum(0.0);
    double weights = 0.0;
    for (const Pixel& b : border) {
      const float c = glm::dot(d, direction(b.x, b.y));
      const double angle2 = std::max(2.0 * (1.0 - static_cast<double>(c)), 1e-12);
      sum += glm::dvec3(panorama.at(b.x, b.y)) / angle2;
      weights += 1.0 / angle2;
    }
    fill[k] = glm::vec3(sum / weights);
  }

  ExtractedSun sun;
  glm::dvec3 irradiance(0.0), weightedDir(0.0);
  float peakExcess = 0.0f;
  for (std::size_t k = 0; k < region.size(); ++k) {
    const Pixel p = region[k];
    const glm::vec3 excess = panorama.at(p.x, p.y) - fill[k];
    const double omega = equirectPixelSolidAngle(p.y, w, h);
    irradiance += glm::dvec3(excess) * omega;
    weightedDir +=
        glm::dvec3(direction(p.x, p.y)) * (static_cast<double>(luminance(excess)) * omega);
    peakExcess = std::max(peakExcess, luminance(excess));
    panorama.at(p.x, p.y) = fill[k];
  }
  sun.irradiance = glm::max(glm::vec3(irradiance), glm::vec3(0.0f));
  sun.pixels = static_cast<int>(region.size());
  sun.peakRatio = ratio;
  Light& light = sun.light;
  light.type = LightType::Sun;
  light.name = "extracted sun";
  light.direction = glm::normalize(glm::vec3(weightedDir));
  light.intensity = luminance(sun.irradiance);
  light.color = light.intensity > 0.0f ? sun.irradiance / light.intensity : glm::vec3(1.0f);
  // A uniform disk of the peak's radiance carrying the same illuminance: its solid angle.
  const double omega = peakExcess > 0.0f ? light.intensity / peakExcess : 0.0;
  const double diameter =
      2.0 * std::acos(std::clamp(1.0 - omega / (2.0 * std::numbers::pi), -1.0, 1.0));
  light.angularDiameter =
      static_cast<float>(std::clamp(diameter, glm::radians(0.05), glm::radians(30.0)));
  return sun;
}

}  // namespace ibl
