#include "ibl/env/equirect.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/env/cubemap.hpp"

namespace ibl {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr float kPiF = std::numbers::pi_v<float>;

// Column x of a map `w` wide, wrapped around the 360-degree seam.
int wrapColumn(int x, int w) {
  x %= w;
  return x < 0 ? x + w : x;
}
}  // namespace

glm::vec2 directionToEquirect(glm::vec3 d) {
  // v = acos(y / |d|) = atan2(sqrt(x^2 + z^2), y): accurate at the poles too.
  const float u = 0.5f + atan2Approx(d.z, d.x) / (2.0f * kPiF);
  const float v = atan2Approx(std::sqrt(d.x * d.x + d.z * d.z), d.y) / kPiF;
  return {u, v};
}

glm::vec3 equirectToDirection(float u, float v) {
  const float phi = 2.0f * kPiF * (u - 0.5f);
  const float theta = kPiF * v;
  const float st = std::sin(theta);
  return {st * std::cos(phi), std::cos(theta), st * std::sin(phi)};
}

double equirectPixelSolidAngle(int y, int width, int height) {
  return 2.0 * kPi / width * (std::cos(kPi * y / height) - std::cos(kPi * (y + 1) / height));
}

glm::vec3 sampleEquirect(const Image& img, float u, float v) {
  const int w = img.width, h = img.height;
  const float fx = u * static_cast<float>(w) - 0.5f;
  const float fy = std::clamp(v * static_cast<float>(h) - 0.5f, 0.0f, static_cast<float>(h - 1));
  const float flx = std::floor(fx), fly = std::floor(fy);
  const float wx = fx - flx, wy = fy - fly;
  const int x0 = wrapColumn(static_cast<int>(flx), w);
  const int x1 = wrapColumn(x0 + 1, w);
  const int y0 = static_cast<int>(fly);
  const int y1 = std::min(y0 + 1, h - 1);
  const glm::vec3 top = img.at(x0, y0) * (1.0f - wx) + img.at(x1, y0) * wx;
  const glm::vec3 bottom = img.at(x0, y1) * (1.0f - wx) + img.at(x1, y1) * wx;
  return top * (1.0f - wy) + bottom * wy;
}

glm::vec3 sampleEquirectCubic(const Image& img, float u, float v, TapRange* range) {
  const int w = img.width, h = img.height;
  const float fx = u * static_cast<float>(w) - 0.5f;
  const float fy = v * static_cast<float>(h) - 0.5f;
  const float flx = std::floor(fx), fly = std::floor(fy);
  const int x0 = static_cast<int>(flx) - 1, y0 = static_cast<int>(fly) - 1;
  glm::vec3 taps[4][4];
  const bool inside = x0 >= 0 && x0 + 3 < w && y0 >= 0 && y0 + 3 < h;  // off the seam and poles
  for (int j = 0; j < 4; ++j) {
    const int y = inside ? y0 + j : std::clamp(y0 + j, 0, h - 1);
    for (int i = 0; i < 4; ++i) taps[j][i] = img.at(inside ? x0 + i : wrapColumn(x0 + i, w), y);
  }
  return reconstructFromWindow(taps, fx - flx, fy - fly, range);
}

glm::vec3 sampleEquirect(const Image& img, glm::vec3 dir) {
  const glm::vec2 uv = directionToEquirect(dir);
  return sampleEquirect(img, uv.x, uv.y);
}

Image downsampleEquirect(const Image& img) {
  if (img.width % 2 != 0 || img.height % 2 != 0)
    fail("equirect downsample", "width and height must be even");
  Image out(img.width / 2, img.height / 2);
  for (int y = 0; y < out.height; ++y) {
    // Pixels of one row share their solid angle: weight the two source rows by theirs.
    const double w0 = equirectPixelSolidAngle(2 * y, img.width, img.height);
    const double w1 = equirectPixelSolidAngle(2 * y + 1, img.width, img.height);
    const double norm = 1.0 / (2.0 * (w0 + w1));
    for (int x = 0; x < out.width; ++x) {
      const glm::dvec3 a = glm::dvec3(img.at(2 * x, 2 * y)) + glm::dvec3(img.at(2 * x + 1, 2 * y));
      const glm::dvec3 b =
          glm::dvec3(img.at(2 * x, 2 * y + 1)) + glm::dvec3(img.at(2 * x + 1, 2 * y + 1));
      out.at(x, y) = glm::vec3((a * w0 + b * w1) * norm);
    }
  }
  return out;
}

glm::dvec3 integrateEquirect(const Image& img) {
  glm::dvec3 total(0.0);
  for (int y = 0; y < img.height; ++y) {
    glm::dvec3 row(0.0);
    for (int x = 0; x < img.width; ++x) row += glm::dvec3(img.at(x, y));
    total += row * equirectPixelSolidAngle(y, img.width, img.height);
  }
  return total;
}

}  // namespace ibl
