#include "ibl/math/sh.hpp"
#include "ibl/core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

namespace ibl {

std::array<float, 9> shBasis9(glm::vec3 d) {
  std::array<float, 9> basis;
  for (int k = 0; k < 9; ++k) basis[k] = shBasis(k, d);
  return basis;
}

Sh9 projectSh9(const CubeMap& cube, int level) {
  const int n = cube.levels[level][0].width;
  const std::vector<double> omega = faceTexelSolidAngles(n);
  // One partial sum per face row, added in a fixed order: the same bits for any thread count.
  std::vector<std::array<glm::dvec3, 9>> rows(static_cast<std::size_t>(kFaceCount) * n);
  parallelFor(0, kFaceCount * n, [&](int row) {
    const int face = row / n, y = row % n;
    auto& acc = rows[row];
    acc.fill(glm::dvec3(0.0));
    for (int x = 0; x < n; ++x) {
      const auto basis = shBasis9(texelDirection(face, x, y, n));
      const glm::dvec3 l = glm::dvec3(cube.levels[level][face].at(x, y)) *
                           omega[static_cast<std::size_t>(y) * n + x];
      for (int k = 0; k < 9; ++k) acc[k] += l * static_cast<double>(basis[k]);
    }
  });
  std::array<glm::dvec3, 9> total{};
  for (const auto& r : rows)
    for (int k = 0; k < 9; ++k) total[k] += r[k];
  Sh9 sh;
  for (int k = 0; k < 9; ++k) sh[k] = glm::vec3(total[k]);
  return sh;
}

glm::vec3 evaluateSh9(const Sh9& sh, glm::vec3 d) {
  const auto basis = shBasis9(d);
  glm::vec3 sum(0.0f);
  for (int k = 0; k < 9; ++k) sum += sh[k] * basis[k];
  return sum;
}

glm::vec3 irradianceSh9(const Sh9& sh, glm::vec3 n) {
  const auto basis = shBasis9(n);
  glm::vec3 sum(0.0f);
  for (int k = 0; k < 9; ++k) sum += sh[k] * (basis[k] * shCosineLobe(shBand(k)));
  return sum;
}

namespace {

// The Lanczos sigma factor of band l: sinc(pi l / (lmax + 1)) with lmax = 2.
float lanczosBandWindow(int l) {
  if (l == 0) return 1.0f;
  const float x = std::numbers::pi_v<float> * static_cast<float>(l) / 3.0f;
  return std::sin(x) / x;
}

}  // namespace

Sh9 windowSh9(const Sh9& sh) {
  return windowSh9(sh, ShWindow::Lanczos);
}

float irradianceLowerBound(const std::array<float, 9>& e) {
  // The basis' constants (Y00, Y1m, the xy/yz/xz terms, 3z^2 - 1, x^2 - y^2).
  constexpr float k0 = 0.282095f, k1 = 0.488603f, kCross = 1.092548f, kZonal = 0.315392f,
                  kSquare = 0.546274f;
  // Turn the band-1 direction onto +z. The bound does not depend on the turn about z, so any x, y
  // completing the frame will do. (cmgen takes x = z x (0, 1, 0), a NaN where the band-1
  // direction is +-Y or zero, and so its widest window there; we compute the bound.)
  const glm::vec3 linear(e[3], e[1], e[2]);
  const float linearLength = glm::length(linear);
  glm::mat3 axes(1.0f);  // columns: the new axes in world coordinates
  if (linearLength > 0.0f) {
    const glm::vec3 z = linear / linearLength;
    const glm::vec3 helper = std::abs(z.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 x = glm::normalize(glm::cross(helper, z));
    axes = glm::mat3(x, glm::cross(z, x), z);
  }
  // Band 2 on the unit sphere is the traceless quadratic form n^T Q n; in the new frame it is
  // axes^T Q axes, whose entries give the turned coefficients back.
  glm::mat3 q;
  q[0][0] = -kZonal * e[6] + kSquare * e[8];
  q[1][1] = -kZonal * e[6] - kSquare * e[8];
  q[2][2] = 2.0f * kZonal * e[6];
  q[0][1] = q[1][0] = 0.5f * kCross * e[4];
  q[1][2] = q[2][1] = 0.5f * kCross * e[5];
  q[0][2] = q[2][0] = 0.5f * kCross * e[7];
  const glm::mat3 turned = glm::transpose(axes) * q * axes;
  const float zonal = turned[2][2] / (2.0f * kZonal);
  const float squareAmplitude =
      kSquare * std::hypot((turned[0][0] - turned[1][1]) / (2.0f * kSquare),
                           2.0f * turned[0][1] / kCross);  // |m| = 2: kSquare * |(e8, e4)|
  const float crossAmplitude =
      kCross * std::hypot(2.0f * turned[1][2] / kCross, 2.0f * turned[0][2] / kCross);

  // Along z: a z^2 + b z + c, with the |m| = 2 part at its azimuthal minimum -amp (1 - z^2).
  const float a = 3.0f * kZonal * zonal + squareAmplitude;
  const float b = k1 * linearLength;
  const float c = k0 * e[0] - kZonal * zonal - squareAmplitude;
  const float zMin = -b / (2.0f * a);
  const float zonalMin = a > 0.0f && zMin >= -1.0f && zMin <= 1.0f ? a * zMin * zMin + b * zMin + c
                                                                   : std::min(a + b + c, a - b + c);
  // The |m| = 1 part, d z sqrt(1 - z^2) at its azimuthal extreme, is -d/2 at z = -1/sqrt 2.
  const float d = crossAmplitude;
  float minimum = zonalMin - 0.5f * d;
  if (minimum >= 0.0f) return minimum;
  const auto f = [=](float z) { return a * z * z + b * z + c + d * z * std::sqrt(1.0f - z * z); };
  const auto newtonStep = [=](float z) {  // f'(z) / f''(z)
    const float s = std::sqrt(1.0f - z * z);
    return (z * z - 1.0f) * (d - 2.0f * d * z * z + (b + 2.0f * a * z) * s) /
           (3.0f * d * z - 2.0f * d * z * z * z - 2.0f * a * std::pow(1.0f - z * z, 1.5f));
  };
  float z = -std::numbers::sqrt2_v<float> / 2.0f, step = 0.0f;
  // cmgen iterates without a limit; 64 steps are far more than converging takes.
  for (int i = 0; i < 64; ++i) {
    minimum = f(z);
    step = newtonStep(z);
    z -= step;
    if (!(std::abs(z) <= 1.0f && std::abs(step) > 1e-5f)) break;
  }
  if (std::abs(z) > 1.0f) minimum = std::min(f(1.0f), f(-1.0f));  // as cmgen: not for a NaN
  return minimum;
}

float cmgenBandWindow(int l, float w) {
  if (l == 0) return 1.0f;
  if (static_cast<float>(l) >= w) return 0.0f;
  const float x = std::numbers::pi_v<float> * static_cast<float>(l) / w;
  return std::pow(std::sin(x) / x, 4.0f);
}

float cmgenShCutoff(const Sh9& radiance) {
  constexpr float kBands = 3.0f;
  float cutoff = kBands * 4.0f + 1.0f;
  for (int channel = 0; channel < 3; ++channel) {
    std::array<float, 9> e;
    for (int k = 0; k < 9; ++k) e[k] = radiance[k][channel] * shCosineLobe(shBand(k));
    const auto windowedBound = [&e](float w) {
      std::array<float, 9> windowed;
      for (int k = 0; k < 9; ++k) windowed[k] = e[k] * cmgenBandWindow(shBand(k), w);
      return irradianceLowerBound(windowed);
    };
    float lo = kBands, hi = cutoff;
    for (int i = 0; i < 16 && lo + 0.1f < hi; ++i) {
      const float mid = 0.5f * (lo + hi);
      (windowedBound(mid) < 0.0f ? hi : lo) = mid;
    }
    cutoff = std::min(cutoff, lo);
  }
  return cutoff;
}

Sh9 windowSh9(const Sh9& radiance, ShWindow window, std::array<float, 3>* factors) {
  std::array<float, 3> band = {1.0f, 1.0f, 1.0f};
  if (window == ShWindow::Lanczos) {
    for (int l = 0; l < 3; ++l) band[l] = lanczosBandWindow(l);
  } else if (window == ShWindow::Cmgen) {
    const float w = cmgenShCutoff(radiance);
    for (int l = 0; l < 3; ++l) band[l] = cmgenBandWindow(l, w);
  }
  if (factors) *factors = band;
  return windowSh9(radiance, band);
}

Sh9 windowSh9(const Sh9& sh, const std::array<float, 3>& bandFactors) {
  Sh9 out = sh;
  for (int k = 0; k < 9; ++k) out[k] *= bandFactors[shBand(k)];
  return out;
}

}  // namespace ibl
