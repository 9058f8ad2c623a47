#include "ibl/env/equirect.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"
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

EquirectCubic::EquirectCubic(const Image& img) : image_(&img), stride_(img.width + 2 * kPad) {
  const int w = img.width, h = img.height, rows = h + 2 * kPad;
  padded_.resize(static_cast<std::size_t>(rows) * stride_);
  parallelFor(0, rows, [&](int py) {
    const int y = std::clamp(py - kPad, 0, h - 1);
    for (int px = 0; px < stride_; ++px) {
      const glm::vec3 t = img.at(wrapColumn(px - kPad, w), y);
      padded_[static_cast<std::size_t>(py) * stride_ + px] = {t.x, t.y, t.z, 0.0f};
    }
  });
  // Window origins x0 + kPad in [0, w], y0 + kPad in [0, h]: the minimum and maximum over 4
  // columns, then over 4 rows of those.
  const int ox = w + 1, oy = h + 1;
  std::vector<std::array<float, 6>> across(static_cast<std::size_t>(rows) * ox);
  parallelFor(0, rows, [&](int py) {
    for (int x = 0; x < ox; ++x) {
      std::array<float, 6> m{};
      for (int c = 0; c < 3; ++c)
        m[c] = m[3 + c] = padded_[static_cast<std::size_t>(py) * stride_ + x][c];
      for (int i = 1; i < 4; ++i)
        for (int c = 0; c < 3; ++c) {
          const float t = padded_[static_cast<std::size_t>(py) * stride_ + x + i][c];
          m[c] = std::min(m[c], t);
          m[3 + c] = std::max(m[3 + c], t);
        }
      across[static_cast<std::size_t>(py) * ox + x] = m;
    }
  });
  steep_.resize(static_cast<std::size_t>(oy) * ox);
  parallelFor(0, oy, [&](int y) {
    for (int x = 0; x < ox; ++x) {
      glm::vec3 lo(0.0f), hi(0.0f);
      for (int j = 0; j < 4; ++j) {
        const auto& m = across[static_cast<std::size_t>(y + j) * ox + x];
        for (int c = 0; c < 3; ++c) {
          lo[c] = j == 0 ? m[c] : std::min(lo[c], m[c]);
          hi[c] = j == 0 ? m[3 + c] : std::max(hi[c], m[3 + c]);
        }
      }
      steep_[static_cast<std::size_t>(y) * ox + x] = windowIsSteep(lo, hi) ? 1 : 0;
    }
  });
}

glm::vec3 EquirectCubic::operator()(float u, float v, TapRange* range) const {
  const int w = image_->width, h = image_->height;
  const float fx = u * static_cast<float>(w) - 0.5f;
  const float fy = v * static_cast<float>(h) - 0.5f;
  const float flx = std::floor(fx), fly = std::floor(fy);
  // Origins in [-kPad, w - kPad] x [-kPad, h - kPad] (u, v within [0, 1], clamped for rounding).
  const int x0 = std::clamp(static_cast<int>(flx) - 1, -kPad, w - kPad);
  const int y0 = std::clamp(static_cast<int>(fly) - 1, -kPad, h - kPad);
  if (range && steep_[static_cast<std::size_t>(y0 + kPad) * (w + 1) + x0 + kPad])
    range->steep = true;
  const glm::vec4 wx = catmullRomWeights(fx - flx), wy = catmullRomWeights(fy - fly);
  float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  for (int j = 0; j < 4; ++j) {
    const std::array<float, 4>* row =
        &padded_[static_cast<std::size_t>(y0 + kPad + j) * stride_ + x0 + kPad];
    float across[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 4; ++c) across[c] += row[i][c] * wx[i];
    for (int c = 0; c < 4; ++c) sum[c] += across[c] * wy[j];
  }
  return {sum[0], sum[1], sum[2]};
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
