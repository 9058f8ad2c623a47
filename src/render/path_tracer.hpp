#pragma once
// Internal to the renderer: the reference, a path tracer over the scene (Embree) lit by the
// environment (the source cube's level 0, piecewise constant over its texels), the scene's
// lights and emissive surfaces, with next-event estimation and multiple importance sampling at
// every vertex and Russian roulette (Veach 1997, section 9.2; pbrt-v4, section 13.4).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "emissive_triangles.hpp"
#include "ibl/core/image.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/light_sampling.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/shared/path_brdf.h"
#include "ray_tracer.hpp"
#include "sampler.hpp"

namespace ibl {

// The environment of the reference: a cube level taken as constant over each texel, sampled
// in proportion to luminance x solid angle (a texel, then a point uniform on its face-plane
// square), so that pdf(w) = p_texel / (A_texel rho(w)) with rho = (1 + sc^2 + tc^2)^(-3/2).
// The texel is drawn as pbrt-v4's PiecewiseConstant2D draws (Pharr et al., 4th ed., section
// A.5.3): a row of the six faces from the first number (the rows' marginal), then a texel of
// the row from the second (its conditional), each by inverting a short CDF; what is left of
// each number places the point in the texel. Nearby numbers give nearby directions, which keeps
// the low-discrepancy numbers' stratification, and the searches run over 6n and n entries.
class EnvironmentSampler {
 public:
  explicit EnvironmentSampler(const std::array<Image, kFaceCount>& level);

  glm::vec3 radiance(glm::vec3 dir) const {
    const auto [face, x, y] = texelOf(dir);
    return level_[face].at(x, y);
  }

  float pdf(glm::vec3 dir) const {
    const auto [face, x, y] = texelOf(dir);
    const std::size_t row = static_cast<std::size_t>(face) * n_ + y;
    const FacePoint fp = directionToFace(dir);
    const float sc = 2.0f * fp.s - 1.0f, tc = 2.0f * fp.t - 1.0f;
    const float q = 1.0f + sc * sc + tc * tc;
    const float invRho = q * std::sqrt(q);  // q^(3/2)
    return static_cast<float>(intervalOf(rowCdf_.data(), row) *
                              intervalOf(columnCdf_.data() + row * n_, x)) *
           invRho / texelArea_;
  }

  // The tables, for the GPU reference's copy: the rows' CDF (6n entries, face-major) and each
  // row's CDF over its n texels, row after row; each ends at 1.
  const std::vector<double>& rowCdf() const { return rowCdf_; }
  const std::vector<double>& columnCdf() const { return columnCdf_; }

  glm::vec3 sample(glm::vec2 xi) const {
    const auto [row, v] = invert(rowCdf_.data(), rowCdf_.size(), xi.x);
    const auto [x, u] = invert(columnCdf_.data() + row * n_, static_cast<std::size_t>(n_), xi.y);
    const int face = static_cast<int>(row / static_cast<std::size_t>(n_));
    const int y = static_cast<int>(row % static_cast<std::size_t>(n_));
    const float inv = 2.0f / static_cast<float>(n_);
    return glm::normalize(faceToDirection(face, (static_cast<float>(x) + u) * inv - 1.0f,
                                          (static_cast<float>(y) + v) * inv - 1.0f));
  }

 private:
  struct TexelIndex {
    int face, x, y;
  };
  TexelIndex texelOf(glm::vec3 dir) const {
    const FacePoint p = directionToFace(dir);
    return {p.face, std::clamp(static_cast<int>(p.s * static_cast<float>(n_)), 0, n_ - 1),
            std::clamp(static_cast<int>(p.t * static_cast<float>(n_)), 0, n_ - 1)};
  }
  // The probability of entry i of a CDF (cdf[i] is the sum of entries 0..i, the last 1).
  static double intervalOf(const double* cdf, std::size_t i) {
    return cdf[i] - (i > 0 ? cdf[i - 1] : 0.0);
  }
  // The entry whose interval holds x, and where in it x lies, in [0, 1].
  struct Inverted {
    std::size_t index;
    float within;
  };
  static Inverted invert(const double* cdf, std::size_t count, float x) {
    const std::size_t i = std::min(
        static_cast<std::size_t>(std::upper_bound(cdf, cdf + count, static_cast<double>(x)) - cdf),
        count - 1);
    const double lo = i > 0 ? cdf[i - 1] : 0.0;
    return {i, static_cast<float>(std::clamp((x - lo) / std::max(cdf[i] - lo, 1e-300), 0.0, 1.0))};
  }
  const std::array<Image, kFaceCount>& level_;
  int n_;
  std::vector<double> rowCdf_;     // over the 6n rows (face-major)
  std::vector<double> columnCdf_;  // per row, over its n texels
  float texelArea_;
};

// What the path tracer reads, shared by all pixels.
struct PathTracerScene {
  const Scene& scene;
  const RayTracer& tracer;
  const EnvironmentSampler& environment;
  const RenderOptions& options;
  const EmissiveTriangles& emitters;  // the scene's emissive triangles, sampled as lights
};

// The directional-albedo tables the reference's material reads (ibl/shared/path_brdf.h), for a
// render of sheen visibility `visibility`: integrated once per process (call
// preparePathTracer() first outside parallel work), alive until it ends.
shared::AlbedoTables referenceAlbedoTables(SheenVisibility visibility);
// The render's shading switches as the shared material reads them.
shared::PathShading pathShading(const RenderOptions& o);

// Computes what tracePath reads once per process (the multiple-scattering table). Call it
// outside parallel work: a table built lazily inside a task could be re-entered by the same
// thread through oneTBB's work stealing.
void preparePathTracer();

// The radiance that surface point `p` at `position` sends toward unit direction `view` (its
// emission included): direct light from every light, the emissive triangles and the
// environment, and (up to options.bounces) the light other surfaces reflect. Unbiased but for the
// environment's texels.
glm::vec3 tracePath(const PathTracerScene& s, SurfacePoint p, glm::vec3 position, glm::vec3 view,
                    Sampler& sampler);

// The nearest light the ray from p along w meets (lights do not hide one another beyond that):
// its index, or -1.
struct NearestLight {
  int index = -1;
  LightHit hit;
};
NearestLight nearestLight(const std::vector<Light>& lights, glm::vec3 p, glm::vec3 w);

// A metal seen by a probe as a diffuse surface of albedo F0 (Lagarde & de Rousiers 2014,
// 4.9.1.2): its specular depends on the view, and it would otherwise be black.
SurfacePoint metalAsDiffuse(SurfacePoint p);

}  // namespace ibl
