#include "ibl/core/stats.hpp"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "ibl/env/equirect.hpp"
#include "ibl/math/color.hpp"

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

std::optional<glm::vec3> brightestDirection(const Environment& env) {
  float best = 0.0f;
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
  if (!(best > 0.0f)) return std::nullopt;
  return dir;
}

namespace {

constexpr int kBlock = 4;  // the block error's block side, pixels

bool inMask(const std::vector<float>* mask, std::size_t i) {
  return !mask || (*mask)[i] > 0.5f;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2) return *mid;
  return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

}  // namespace

FrameErrors frameErrors(const Image& a, const Image& b, const std::vector<float>* mask) {
  FrameErrors f;
  double absDiff = 0.0, refSum = 0.0;
  std::size_t pixels = 0, off = 0;
  std::vector<double> blockErrors;
  for (int by = 0; by < b.height; by += kBlock)
    for (int bx = 0; bx < b.width; bx += kBlock) {
      double la = 0.0, lr = 0.0;
      int n = 0;
      for (int y = by; y < std::min(by + kBlock, b.height); ++y)
        for (int x = bx; x < std::min(bx + kBlock, b.width); ++x) {
          const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(b.width) +
                                static_cast<std::size_t>(x);
          if (!inMask(mask, i)) continue;
          const double l = luminance(a.pixels[i]), r = luminance(b.pixels[i]);
          absDiff += std::abs(l - r);
          refSum += r;
          if ((l > 0.0 || r > 0.0) && (l >= 2.0 * r || r >= 2.0 * l)) ++off;
          la += l;
          lr += r;
          ++n;
        }
      pixels += static_cast<std::size_t>(n);
      if (n == 0) continue;
      if (lr > 0.0)
        blockErrors.push_back(std::abs(la - lr) / lr);
      else
        ++f.blackBlocks;
    }
  f.frameError = refSum > 0.0 ? absDiff / refSum : 0.0;
  f.offBy2x = pixels ? static_cast<double>(off) / static_cast<double>(pixels) : 0.0;
  f.blocks = blockErrors.size();
  f.medianBlockError = median(std::move(blockErrors));
  return f;
}

ImageComparison compareImages(const Image& a, const Image& b, const std::vector<float>* mask) {
  ImageComparison result;
  result.frame = frameErrors(a, b, mask);
  double sq[4] = {}, ref[4] = {}, rel[4] = {}, peak = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    if (mask && (*mask)[i] <= 0.5f) continue;
    ++result.pixels;
    for (int c = 0; c < 3; ++c) {
      const double x = a.pixels[i][c], y = b.pixels[i][c], d = x - y;
      for (int k : {c, 3}) {
        sq[k] += d * d;
        ref[k] += y * y;
        rel[k] += std::abs(d) / (std::abs(y) + 1e-3);
      }
      auto& ch = result.channel[c];
      ch.maxError = std::max(ch.maxError, std::abs(d));
      result.overall.maxError = std::max(result.overall.maxError, std::abs(d));
      peak = std::max(peak, y);
    }
  }
  const double n = static_cast<double>(std::max<std::size_t>(result.pixels, 1));
  for (int k = 0; k < 4; ++k) {
    ChannelErrors& e = k < 3 ? result.channel[k] : result.overall;
    const double count = k < 3 ? n : 3.0 * n;
    e.rmse = std::sqrt(sq[k] / count);
    e.relativeMse = ref[k] > 0.0 ? sq[k] / ref[k] : 0.0;
    e.meanRelativeError = rel[k] / count;
    e.psnr = e.rmse > 0.0 && peak > 0.0 ? 20.0 * std::log10(peak / e.rmse) : INFINITY;
  }
  return result;
}

Image errorFalseColor(const Image& a, const Image& b, double scale) {
  Image out(a.width, a.height);
  const glm::vec3 ramp[5] = {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const double e = std::abs(luminance(a.pixels[i]) - luminance(b.pixels[i])) /
                     (std::abs(luminance(b.pixels[i])) + 1e-3);
    const float t = static_cast<float>(std::clamp(e / scale, 0.0, 1.0)) * 4.0f;
    const int k = std::min(static_cast<int>(t), 3);
    out.pixels[i] = glm::mix(ramp[k], ramp[k + 1], t - static_cast<float>(k));
  }
  return out;
}

}  // namespace ibl
