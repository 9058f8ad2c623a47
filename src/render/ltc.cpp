#include "ibl/render/ltc.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include "ibl/core/parallel.hpp"
#include "ibl/shared/brdf.h"
#include "ibl/shared/ltc.h"
#include "ibl/shared/sampling.h"

namespace ibl {
namespace {

#include "ltc_table.inc"  // kLtcTableSize, kLtcTable, kLtcNormTable: by tools/ltc_fit.cpp

static_assert(sizeof(kLtcTable) == sizeof(float) * 4 * kLtcTableSize * kLtcTableSize);
static_assert(sizeof(kLtcNormTable) == sizeof(kLtcTable));

// The smallest alpha the shading uses (lights.h clamps alpha the same way).
constexpr float kMinAlpha = 1e-3f;

// The fitted lobe: GGX at alpha seen from v = (sin theta, 0, cos theta), no Fresnel, with the
// sampling of its visible normals.
struct GgxLobe {
  float alpha = 1.0f;
  glm::vec3 v{0.0f, 0.0f, 1.0f};
  float albedo = 1.0f;  // the integral of the unnormalized lobe over the hemisphere

  // D(h) G2 / (4 n.v): the lobe times the cosine, unnormalized (0 below the horizon).
  [[nodiscard]] float value(glm::vec3 l) const {
    if (l.z <= 0.0f) return 0.0f;
    const glm::vec3 h = glm::normalize(v + l);
    return shared::ggxDistribution(h.z, alpha) *
           shared::smithGgxCorrelatedVisibility(v.z, l.z, alpha) * l.z;
  }
  // The density of sampleDirection: G1(v) D(h) / (4 n.v) (Heitz 2018).
  [[nodiscard]] float pdf(glm::vec3 l) const {
    const glm::vec3 h = glm::normalize(v + l);
    if (h.z <= 0.0f || glm::dot(v, h) <= 0.0f) return 0.0f;
    return shared::smithGgxMasking(v.z, alpha) * shared::ggxDistribution(h.z, alpha) / (4.0f * v.z);
  }
  [[nodiscard]] glm::vec3 sampleDirection(glm::vec2 xi) const {
    const glm::vec3 h = shared::sampleGgxVisibleNormal(v, xi, alpha);
    return 2.0f * glm::dot(v, h) * h - v;
  }
};

glm::vec2 stratified(int i, int j, int n) {
  return {(static_cast<float>(i) + 0.5f) / static_cast<float>(n),
          (static_cast<float>(j) + 0.5f) / static_cast<float>(n)};
}

GgxLobe makeLobe(float alpha, float cosTheta) {
  GgxLobe lobe;
  lobe.alpha = alpha;
  const float c = std::clamp(cosTheta, 1e-3f, 1.0f);
  lobe.v = glm::vec3(std::sqrt(1.0f - c * c), 0.0f, c);
  constexpr int n = 96;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const glm::vec3 l = lobe.sampleDirection(stratified(i, j, n));
      const float p = lobe.pdf(l);
      if (p > 0.0f) sum += lobe.value(l) / p;
    }
  lobe.albedo = static_cast<float>(sum / (n * n));
  return lobe;
}

// Heitz et al. 2016's averaged terms of the lobe (their fitting code's computeAvgTerms, written
// anew), by importance sampling the lobe with n^2 stratified directions: the norm, the integral of
// rho cos over the hemisphere (no Fresnel; the LTC's magnitude); the Fresnel term, the same
// integral weighted by Schlick's (1 - v.h)^5 (so that the lobe with Schlick's Fresnel integrates to
// F0 (norm - fresnel) + f90 fresnel, as their shader scales the LTC); and the mean direction, the
// integral of rho cos l over the norm (x, z: the lobe is symmetric about the xz plane).
LtcNorm lobeAverages(const GgxLobe& lobe, int n) {
  double norm = 0.0, fresnel = 0.0;
  glm::dvec3 mean(0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const glm::vec3 l = lobe.sampleDirection(stratified(i, j, n));
      const float p = lobe.pdf(l);
      if (p <= 0.0f) continue;
      const double w = lobe.value(l) / p;
      const double vh = std::max(0.0f, glm::dot(lobe.v, glm::normalize(lobe.v + l)));
      norm += w;
      fresnel += w * std::pow(1.0 - vh, 5.0);
      mean += w * glm::dvec3(l);
    }
  const double count = static_cast<double>(n) * n;
  LtcNorm a;
  a.norm = static_cast<float>(norm / count);
  a.fresnel = static_cast<float>(fresnel / count);
  a.meanDirection = norm > 0.0 ? glm::vec2(mean.x / norm, mean.z / norm) : glm::vec2(0.0f, 1.0f);
  return a;
}

// The lobe's mean direction's angle from the normal, in the plane of v.
float meanDirectionAngle(const LtcNorm& a) {
  return std::atan2(a.meanDirection.x, a.meanDirection.y);
}

// M (rows) and M^-1 (as ltc.h stores it) from the parameters (m11, m22, m13, m31), around the
// mean direction phi: M = R(phi) [[m11, 0, m13], [0, m22, 0], [m31, 0, 1]].
struct LtcMatrices {
  std::array<glm::vec3, 3> rows;
  glm::vec4 entry;
};
LtcMatrices ltcMatrices(glm::vec4 params, float phi) {
  const float m22 = std::max(std::abs(params.y), 1e-7f);
  const float c = std::cos(phi), s = std::sin(phi);
  // The xz block [[a, b], [d, e]] of R(phi) S.
  const float a = c * params.x + s * params.w, b = c * params.z + s;
  const float d = -s * params.x + c * params.w, e = -s * params.z + c;
  float det = a * e - b * d;
  if (std::abs(det) < 1e-12f) det = 1e-12f;
  LtcMatrices m;
  m.rows = {glm::vec3(a, 0.0f, b), glm::vec3(0.0f, m22, 0.0f), glm::vec3(d, 0.0f, e)};
  // M^-1, scaled by m22 so that its middle entry is 1.
  m.entry = glm::vec4(e, -b, -d, a) * (m22 / det);
  return m;
}

glm::vec3 ltcSampleDirection(const LtcMatrices& m, glm::vec2 xi) {
  const glm::vec3 o = shared::sampleCosineHemisphere(xi);
  return glm::normalize(
      glm::vec3(glm::dot(m.rows[0], o), glm::dot(m.rows[1], o), glm::dot(m.rows[2], o)));
}

// The integral of |target - LTC|^k, by multiple importance sampling (balance heuristic) with
// n^2 samples of each distribution.
double ltcDistance(const GgxLobe& lobe, const LtcMatrices& m, int n, int k) {
  double sum = 0.0;
  const auto add = [&](glm::vec3 l) {
    const double target = lobe.value(l) / lobe.albedo;
    const double ltc = shared::ltcDensity(m.entry, l);
    const double pdf = lobe.pdf(l) + ltc;
    if (pdf <= 0.0) return;
    const double d = std::abs(target - ltc);
    sum += (k == 1 ? d : d * d * d) / pdf;
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const glm::vec2 xi = stratified(i, j, n);
      add(lobe.sampleDirection(xi));
      add(ltcSampleDirection(m, xi));
    }
  return sum / (static_cast<double>(n) * n);
}

// Nelder-Mead's downhill simplex (Nelder & Mead 1965) in four dimensions.
template <typename F>
glm::vec4 minimizeNelderMead(const F& f, glm::vec4 start, glm::vec4 step, int iterations) {
  constexpr int kDim = 4;
  std::array<glm::vec4, kDim + 1> x{};
  std::array<double, kDim + 1> fx{};
  for (int i = 0; i <= kDim; ++i) {
    x[i] = start;
    if (i > 0) x[i][i - 1] += step[i - 1];
    fx[i] = f(x[i]);
  }
  for (int it = 0; it < iterations; ++it) {
    std::array<int, kDim + 1> order{};
    for (int i = 0; i <= kDim; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return fx[a] < fx[b]; });
    const int best = order[0], worst = order[kDim], second = order[kDim - 1];
    if (fx[worst] - fx[best] <= 1e-7 * std::abs(fx[best]) + 1e-12) break;
    glm::vec4 centroid(0.0f);
    for (int i = 0; i < kDim; ++i) centroid += x[order[i]] / static_cast<float>(kDim);
    const glm::vec4 reflected = centroid + (centroid - x[worst]);
    const double fr = f(reflected);
    if (fr < fx[best]) {
      const glm::vec4 expanded = centroid + 2.0f * (centroid - x[worst]);
      const double fe = f(expanded);
      x[worst] = fe < fr ? expanded : reflected;
      fx[worst] = std::min(fe, fr);
    } else if (fr < fx[second]) {
      x[worst] = reflected;
      fx[worst] = fr;
    } else {
      const bool outside = fr < fx[worst];
      const glm::vec4 contracted = outside ? centroid + 0.5f * (reflected - centroid)
                                           : centroid + 0.5f * (x[worst] - centroid);
      const double fc = f(contracted);
      if (fc < std::min(fr, fx[worst])) {
        x[worst] = contracted;
        fx[worst] = fc;
      } else {  // shrink toward the best
        for (int i = 0; i <= kDim; ++i)
          if (i != best) {
            x[i] = x[best] + 0.5f * (x[i] - x[best]);
            fx[i] = f(x[i]);
          }
      }
    }
  }
  return x[static_cast<std::size_t>(std::min_element(fx.begin(), fx.end()) - fx.begin())];
}

}  // namespace

const LtcTable& ltcGgxTable() {
  static const LtcTable table{
      kLtcTableSize,
      std::span<const glm::vec4>(reinterpret_cast<const glm::vec4*>(kLtcTable),
                                 static_cast<std::size_t>(kLtcTableSize) * kLtcTableSize),
      std::span<const glm::vec4>(reinterpret_cast<const glm::vec4*>(kLtcNormTable),
                                 static_cast<std::size_t>(kLtcTableSize) * kLtcTableSize)};
  return table;
}

namespace {
glm::vec4 lookup(std::span<const glm::vec4> entries, int size, float roughness, float NoV) {
  const glm::vec2 p = shared::ltcTablePosition(roughness, NoV, static_cast<float>(size));
  const int x0 = std::min(static_cast<int>(p.x), size - 2);
  const int y0 = std::min(static_cast<int>(p.y), size - 2);
  const float fx = p.x - static_cast<float>(x0), fy = p.y - static_cast<float>(y0);
  const auto at = [&](int i, int j) { return entries[static_cast<std::size_t>(j) * size + i]; };
  return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx),
                  glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
}
}  // namespace

glm::vec4 ltcTableLookup(float roughness, float NoV) {
  const LtcTable& t = ltcGgxTable();
  return lookup(t.entries, t.size, roughness, NoV);
}

glm::vec4 ltcNormLookup(float roughness, float NoV) {
  const LtcTable& t = ltcGgxTable();
  return lookup(t.norms, t.size, roughness, NoV);
}

LtcNorm ltcLobeAverages(float alpha, float cosTheta, int samples) {
  return lobeAverages(makeLobe(alpha, cosTheta), samples);
}

float ltcColumnAlpha(int column, int size) {
  const float r = static_cast<float>(column) / static_cast<float>(size - 1);
  return std::max(shared::alphaFromRoughness(r), kMinAlpha);
}

float ltcRowCosTheta(int row, int size) {
  const float t = static_cast<float>(row) / static_cast<float>(size - 1);
  return 1.0f - t * t;
}

float ltcFitError(glm::vec4 entry, float alpha, float cosTheta, int samples) {
  const GgxLobe lobe = makeLobe(alpha, cosTheta);
  LtcMatrices m;
  m.entry = entry;
  // M from the entry: the inverse of [[x, 0, y], [0, 1, 0], [z, 0, w]].
  const float det = entry.x * entry.w - entry.y * entry.z;
  m.rows = {glm::vec3(entry.w / det, 0.0f, -entry.y / det), glm::vec3(0.0f, 1.0f, 0.0f),
            glm::vec3(-entry.z / det, 0.0f, entry.x / det)};
  return static_cast<float>(ltcDistance(lobe, m, samples, 1));
}

LtcFit fitLtc(float alpha, float cosTheta, glm::vec4 start, bool isotropic,
              const LtcFitOptions& options) {
  const GgxLobe lobe = makeLobe(alpha, cosTheta);
  const LtcNorm averages = lobeAverages(lobe, 128);
  // Seen along the normal the lobe is round about it (Heitz et al.'s fit at theta = 0): one
  // parameter, m11 = m22, m13 = m31 = 0, no rotation.
  const float phi = isotropic ? 0.0f : meanDirectionAngle(averages);
  const auto expand = [&](glm::vec4 p) { return isotropic ? glm::vec4(p.x, p.x, 0.0f, 0.0f) : p; };
  const auto error = [&](glm::vec4 p) {
    return ltcDistance(lobe, ltcMatrices(expand(p), phi), options.samples, options.exponent);
  };
  glm::vec4 step;
  for (int i = 0; i < 4; ++i) step[i] = 0.1f * std::max(std::abs(start[i]), alpha);
  if (isotropic) step = glm::vec4(step.x, 0.0f, 0.0f, 0.0f);
  // Two rounds: the second restarts the simplex at the first's minimum.
  glm::vec4 p = minimizeNelderMead(error, start, step, 400);
  p = minimizeNelderMead(error, p, 0.5f * step, 300);
  LtcFit fit;
  fit.parameters = expand(p);
  fit.entry = ltcMatrices(fit.parameters, phi).entry;
  fit.norm = averages;
  fit.error = ltcFitError(fit.entry, alpha, cosTheta, 64);
  return fit;
}

std::vector<LtcFit> fitLtcTable(int size, const std::function<void(float)>& progress,
                                const LtcFitOptions& options) {
  std::vector<LtcFit> table(static_cast<std::size_t>(size) * size);
  // Heitz et al.'s initialization: the row at n.v = 1 first, isotropic, from the roughest column
  // (the cosine itself, m11 = m22 = 1) toward the smoothest, each fit from its rougher neighbour;
  // then each column (in parallel) from n.v = 1 toward grazing, each row from the previous one.
  glm::vec4 start(1.0f, 1.0f, 0.0f, 0.0f);
  for (int column = size - 1; column >= 0; --column) {
    const LtcFit fit = fitLtc(ltcColumnAlpha(column, size), 1.0f, start, true, options);
    table[static_cast<std::size_t>(column)] = fit;
    start = fit.parameters;
  }
  std::atomic<int> done{0};
  parallelFor(0, size, [&](int column) {
    const float alpha = ltcColumnAlpha(column, size);
    glm::vec4 previous = table[static_cast<std::size_t>(column)].parameters;
    for (int row = 1; row < size; ++row) {
      const LtcFit fit = fitLtc(alpha, ltcRowCosTheta(row, size), previous, false, options);
      table[static_cast<std::size_t>(row) * size + column] = fit;
      previous = fit.parameters;
    }
    const int finished = ++done;
    if (progress) progress(static_cast<float>(finished) / static_cast<float>(size));
  });
  return table;
}

}  // namespace ibl
