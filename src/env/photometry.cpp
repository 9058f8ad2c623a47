#include "ibl/env/photometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <fmt/core.h>
#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/env/equirect.hpp"
#include "ibl/math/color.hpp"

namespace ibl {

namespace {

constexpr double kPi = std::numbers::pi;

// The images of level 0: an equirect's one, or a cube's six faces.
std::vector<const Image*> levelZero(const Environment& env) {
  std::vector<const Image*> images;
  if (env.isCube()) {
    if (env.cube.levels.empty()) return images;
    for (const Image& face : env.cube.levels[0]) images.push_back(&face);
  } else {
    images.push_back(&env.equirect);
  }
  return images;
}

// The projected solid angle, integral of max(w . up, 0) dw, of the spherical polygon through
// the points `p` (any orientation, not through the origin): clipped to y >= 0, then Lambert's
// formula, 1/2 sum over the edges of the angle they subtend times the y of their plane's unit
// normal.
double projectedSolidAngle(const std::vector<glm::dvec3>& polygon) {
  std::vector<glm::dvec3> clipped;
  clipped.reserve(polygon.size() + 2);
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec3& a = polygon[i];
    const glm::dvec3& b = polygon[(i + 1) % polygon.size()];
    if (a.y >= 0.0) clipped.push_back(a);
    if ((a.y >= 0.0) != (b.y >= 0.0)) {
      const double t = a.y / (a.y - b.y);
      glm::dvec3 c = a + t * (b - a);
      c.y = 0.0;
      clipped.push_back(c);
    }
  }
  if (clipped.size() < 3) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < clipped.size(); ++i) {
    const glm::dvec3& a = clipped[i];
    const glm::dvec3& b = clipped[(i + 1) % clipped.size()];
    const glm::dvec3 n = glm::cross(a, b);
    const double length = glm::length(n);
    if (length == 0.0) continue;
    sum += std::atan2(length, glm::dot(a, b)) * n.y / length;
  }
  return 0.5 * std::abs(sum);
}

// Horizontal illuminance of one n x n face: sum of Y(L) x the texel's projected solid angle,
// row by row (each row's sum in a fixed order: the same result with any number of threads).
double faceIlluminance(const Image& face, int f) {
  const int n = face.width;
  const glm::dvec3 center(faceAxis(f, 0)), sAxis(faceAxis(f, 1)), tAxis(faceAxis(f, 2));
  const auto corner = [&](int x, int y) {
    return center + (2.0 * x / n - 1.0) * sAxis + (2.0 * y / n - 1.0) * tAxis;
  };
  std::vector<double> rows(static_cast<std::size_t>(n), 0.0);
  parallelFor(0, n, [&](int y) {
    double row = 0.0;
    std::vector<glm::dvec3> quad(4);
    for (int x = 0; x < n; ++x) {
      quad[0] = corner(x, y);
      quad[1] = corner(x + 1, y);
      quad[2] = corner(x + 1, y + 1);
      quad[3] = corner(x, y + 1);
      if (quad[0].y <= 0.0 && quad[1].y <= 0.0 && quad[2].y <= 0.0 && quad[3].y <= 0.0) continue;
      const double y709 = luminance(face.at(x, y));
      if (y709 == 0.0) continue;
      row += y709 * projectedSolidAngle(quad);
    }
    rows[static_cast<std::size_t>(y)] = row;
  });
  double total = 0.0;
  for (double r : rows) total += r;
  return total;
}

double equirectIlluminance(const Image& img) {
  const int w = img.width, h = img.height;
  double total = 0.0;
  for (int y = 0; y < h; ++y) {
    const double theta0 = kPi * y / h;
    if (theta0 >= 0.5 * kPi) break;
    const double theta1 = std::min(kPi * (y + 1) / h, 0.5 * kPi);
    const double s0 = std::sin(theta0), s1 = std::sin(theta1);
    // The integral of cos(theta) sin(theta) over the row, times the pixel's 2 pi / w of azimuth.
    const double weight = kPi / w * (s1 * s1 - s0 * s0);
    double row = 0.0;
    for (int x = 0; x < w; ++x) row += luminance(img.at(x, y));
    total += row * weight;
  }
  return total;
}

}  // namespace

double horizontalIlluminance(const Environment& env) {
  if (!env.isCube()) return env.equirect.empty() ? 0.0 : equirectIlluminance(env.equirect);
  if (env.cube.levels.empty()) return 0.0;
  double total = 0.0;
  for (int f = 0; f < kFaceCount; ++f) total += faceIlluminance(env.cube.levels[0][f], f);
  return total;
}

double horizontalIlluminance(const Light& sun) {
  if (sun.type != LightType::Sun) return 0.0;
  const glm::vec3 d = glm::normalize(sun.direction);
  return static_cast<double>(sun.intensity) * luminance(sun.color) *
         std::max(static_cast<double>(d.y), 0.0);
}

double horizontalIlluminance(const Environment& env, std::span<const Light> lights) {
  double total = horizontalIlluminance(env);
  for (const Light& light : lights) total += horizontalIlluminance(light);
  return total;
}

LuminanceRange luminanceRange(const Environment& env) {
  // Each texel's luminance and solid angle, visited three times: the extremes, the sum and the
  // texels that are 0; a histogram of log luminance between the extremes (2^16 bins), which
  // finds the median's bin; the texels of that bin, sorted: the exact median, without holding
  // or sorting every texel.
  const std::vector<const Image*> images = levelZero(env);
  LuminanceRange range;
  if (images.empty() || images[0]->empty()) return range;
  std::vector<double> cubeWeights;
  if (env.isCube()) cubeWeights = faceTexelSolidAngles(images[0]->width);
  const auto visit = [&](const auto& body) {
    for (const Image* img : images)
      for (int y = 0; y < img->height; ++y) {
        const double rowWeight =
            env.isCube() ? 0.0 : equirectPixelSolidAngle(y, img->width, img->height);
        for (int x = 0; x < img->width; ++x) {
          const double w =
              env.isCube() ? cubeWeights[static_cast<std::size_t>(y) * img->width + x] : rowWeight;
          body(static_cast<double>(luminance(img->at(x, y))), w);
        }
      }
  };
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0, positiveLo = lo;
  double sum = 0.0, weights = 0.0, zeroWeight = 0.0;
  visit([&](double l, double w) {
    lo = std::min(lo, l);
    hi = std::max(hi, l);
    if (l > 0.0)
      positiveLo = std::min(positiveLo, l);
    else
      zeroWeight += w;
    sum += l * w;
    weights += w;
  });
  range.min = lo;
  range.max = hi;
  range.mean = weights > 0.0 ? sum / weights : 0.0;
  const double half = 0.5 * weights;
  if (zeroWeight >= half || !(hi > 0.0)) return range;  // the median is 0 (or all is dark)
  constexpr int kBins = 1 << 16;
  const double logLo = std::log2(positiveLo), logHi = std::log2(hi);
  const double span = std::max(logHi - logLo, 1e-12);
  const auto binOf = [&](double l) {
    return std::clamp(static_cast<int>((std::log2(l) - logLo) / span * kBins), 0, kBins - 1);
  };
  std::vector<double> histogram(kBins, 0.0);
  visit([&](double l, double w) {
    if (!(l > 0.0)) return;
    const int bin =
        std::clamp(static_cast<int>((std::log2(l) - logLo) / span * kBins), 0, kBins - 1);
    histogram[static_cast<std::size_t>(bin)] += w;
  });
  double below = zeroWeight;
  int median = kBins - 1;
  for (int b = 0; b < kBins; ++b) {
    const double inBin = histogram[static_cast<std::size_t>(b)];
    if (below + inBin >= half) {
      median = b;
      break;
    }
    below += inBin;
  }
  // The texels of the median's bin (a few), in order: the exact weighted median among them.
  std::vector<std::pair<double, double>> candidates;
  visit([&](double l, double w) {
    if (l > 0.0 && binOf(l) == median) candidates.emplace_back(l, w);
  });
  std::sort(candidates.begin(), candidates.end());
  range.median = candidates.empty() ? hi : candidates.back().first;
  for (const auto& [l, w] : candidates) {
    below += w;
    if (below >= half) {
      range.median = l;
      break;
    }
  }
  return range;
}

void scaleEnvironment(Environment& env, double factor, std::string_view name) {
  if (!(factor > 0.0) || !std::isfinite(factor))
    fail(name, fmt::format("cannot scale by {}: the factor must be positive and finite", factor));
  std::vector<Image*> images;
  if (!env.equirect.empty()) images.push_back(&env.equirect);
  for (auto& level : env.cube.levels)
    for (Image& face : level) images.push_back(&face);
  float largest = 0.0f;
  for (const Image* img : images)
    for (const glm::vec3& p : img->pixels)
      largest = std::max(largest, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
  if (static_cast<double>(largest) * factor > std::numeric_limits<float>::max())
    fail(name, fmt::format("scaled by {:g}, its largest value {:g} would exceed the range of a "
                           "float (3.4e38)",
                           factor, largest));
  const float k = static_cast<float>(factor);
  for (Image* img : images)
    for (glm::vec3& p : img->pixels) p *= k;
}

double illuminanceScale(double measured, double target, std::string_view name) {
  if (!(target > 0.0) || !std::isfinite(target))
    fail(name,
         fmt::format("cannot bring it to {} lux: the target must be positive and finite", target));
  if (!(measured > 0.0) || !std::isfinite(measured))
    fail(name, fmt::format("its horizontal illuminance is {} lux (no light above the horizon): no "
                           "factor brings it to {} lux",
                           measured, target));
  return target / measured;
}

}  // namespace ibl
