#include "ibl/bake/dfg.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "ibl/core/parallel.hpp"
#include "ibl/core/progress.hpp"
#include "ibl/math/brdf.hpp"
#include "ibl/math/sampling.hpp"

namespace ibl {

namespace {

// The integration points: the Hammersley set on the samplers' unit square, equal weights.
// (Product Gauss rules do worse here: the GGX tail makes the integrands steep near the edge of
// the square.)
// The points as flat arrays (what does not depend on (n.v, r)): disk points for the
// visible-normal sampler and cosine-distributed directions.
struct QuadratureNodes {
  std::vector<float> diskX, diskY, cosX, cosY, cosZ;
  explicit QuadratureNodes(int samples) {
    for (int k = 0; k < samples; ++k) {
      const glm::vec2 xi =
          hammersley(static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(samples));
      const glm::vec2 disk = uniformDiskPoint(xi);
      const glm::vec3 c = sampleCosineHemisphere(xi);
      diskX.push_back(disk.x);
      diskY.push_back(disk.y);
      cosX.push_back(c.x);
      cosY.push_back(c.y);
      cosZ.push_back(c.z);
    }
  }
};

// Branch-free over the points so that it vectorizes; compiled for AVX-512, AVX2, baseline.
#if defined(__x86_64__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
glm::vec3
integrateDfgWith(float NoV, float roughness, const QuadratureNodes& q) {
  const float alpha = alphaFromRoughness(roughness);
  const glm::vec3 v(std::sqrt(std::max(0.0f, 1.0f - NoV * NoV)), 0.0f, NoV);
  const float g1 = smithGgxMasking(NoV, alpha);
  const VisibleNormalFrame visibleNormals = visibleNormalFrame(v, alpha);
  glm::vec3 sum(0.0f);
  const std::size_t n = q.diskX.size();
  for (std::size_t k = 0; k < n; ++k) {
    const glm::vec3 h = visibleNormalFromDisk(visibleNormals, {q.diskX[k], q.diskY[k]});
    const glm::vec3 l(q.cosX[k], q.cosY[k], q.cosZ[k]);
    sum += shared::dfgIntegrand(v, alpha, roughness, g1, h, l);
  }
  return sum / static_cast<float>(n);
}

}  // namespace

glm::vec3 integrateDfg(float NoV, float roughness, int samples) {
  return integrateDfgWith(NoV, roughness, QuadratureNodes(samples));
}

Image integrateDfgLut(int width, int height, int samples, const ProgressFn& progress,
                      const std::string& stage) {
  Image lut(width, height);
  const QuadratureNodes nodes(samples);
  ProgressCounter rows(progress, stage, height);
  parallelFor(0, height, [&](int j) {
    const float r = (static_cast<float>(j) + 0.5f) / static_cast<float>(height);
    for (int i = 0; i < width; ++i)
      lut.at(i, j) =
          integrateDfgWith((static_cast<float>(i) + 0.5f) / static_cast<float>(width), r, nodes);
    rows.advance();
  });
  return lut;
}

namespace {

// The half vectors of the sheen integral: Hammersley points mapped uniformly onto the
// hemisphere, computed once per table.
std::vector<glm::vec3> uniformHalfVectors(int samples) {
  std::vector<glm::vec3> h;
  h.reserve(static_cast<std::size_t>(samples));
  for (int k = 0; k < samples; ++k) {
    const glm::vec2 xi =
        hammersley(static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(samples));
    const float cosTheta = 1.0f - xi.y;
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const float phi = 2.0f * std::numbers::pi_v<float> * xi.x;
    h.emplace_back(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
  }
  return h;
}

float integrateSheenDfgWith(float NoV, float roughness, const std::vector<glm::vec3>& halfVectors,
                            SheenVisibility visibility) {
  const float alpha = alphaFromRoughness(roughness);
  const glm::vec3 v(std::sqrt(std::max(0.0f, 1.0f - NoV * NoV)), 0.0f, NoV);
  double sum = 0.0;
  for (const glm::vec3& h : halfVectors) {
    const float VoH = glm::dot(v, h);
    const float NoL = 2.0f * VoH * h.z - NoV;
    if (NoL <= 0.0f || VoH <= 0.0f) continue;
    sum += shared::charlieDistribution(h.z, alpha) * sheenVisibility(visibility, NoV, NoL, alpha) *
           NoL * 4.0f * VoH;
  }
  return static_cast<float>(sum * 2.0 * std::numbers::pi / static_cast<double>(halfVectors.size()));
}

}  // namespace

// The sheen table: E(v) = integral of D_charlie(h) V(v, l) (n.l) dl over l, integrated over
// half vectors drawn uniformly on the hemisphere (as glTF-IBL-Sampler's LUT_CharlieUniform and
// Filament's cmgen cloth DFG do): dl = 4 (v.h) dh and the pdf of h is 1 / (2 pi), so each
// point adds D V (n.l) 4 (v.h) 2 pi. Uniform half vectors keep the points where the Charlie
// lobe lives, near the horizon, for every roughness.
float integrateSheenDfg(float NoV, float roughness, int samples, SheenVisibility visibility) {
  return integrateSheenDfgWith(NoV, roughness, uniformHalfVectors(samples), visibility);
}

Image integrateSheenDfgLut(int width, int height, int samples, SheenVisibility visibility,
                           const ProgressFn& progress, const std::string& stage) {
  Image lut(width, height);
  const std::vector<glm::vec3> halfVectors = uniformHalfVectors(samples);
  ProgressCounter rows(progress, stage, height);
  parallelFor(0, height, [&](int j) {
    const float r = (static_cast<float>(j) + 0.5f) / static_cast<float>(height);
    for (int i = 0; i < width; ++i) {
      const float e = integrateSheenDfgWith(
          (static_cast<float>(i) + 0.5f) / static_cast<float>(width), r, halfVectors, visibility);
      lut.at(i, j) = glm::vec3(e, 0.0f, 0.0f);
    }
    rows.advance();
  });
  return lut;
}

glm::vec3 sampleDfgLut(const Image& lut, float NoV, float roughness) {
  const float fx = std::clamp(NoV * static_cast<float>(lut.width) - 0.5f, 0.0f,
                              static_cast<float>(lut.width - 1));
  const float fy = std::clamp(roughness * static_cast<float>(lut.height) - 0.5f, 0.0f,
                              static_cast<float>(lut.height - 1));
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const int x1 = std::min(x0 + 1, lut.width - 1), y1 = std::min(y0 + 1, lut.height - 1);
  const float wx = fx - static_cast<float>(x0), wy = fy - static_cast<float>(y0);
  return (lut.at(x0, y0) * (1.0f - wx) + lut.at(x1, y0) * wx) * (1.0f - wy) +
         (lut.at(x0, y1) * (1.0f - wx) + lut.at(x1, y1) * wx) * wy;
}

}  // namespace ibl
