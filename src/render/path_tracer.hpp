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
#include "ray_tracer.hpp"

namespace ibl {

// PCG32 (O'Neill 2014): small, fast, and one stream per pixel makes renders reproducible.
class Random {
 public:
  Random(std::uint64_t seed, std::uint64_t stream) : inc_((stream << 1u) | 1u) {
    next();
    state_ += seed;
    next();
  }
  float uniform() { return static_cast<float>(next() >> 8) * (1.0f / 16777216.0f); }
  glm::vec2 uniform2() { return {uniform(), uniform()}; }

 private:
  std::uint32_t next() {
    const std::uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }
  std::uint64_t state_ = 0, inc_;
};

// The environment of the reference: a cube level taken as constant over each texel, sampled
// in proportion to luminance x solid angle (a texel, then a point uniform on its face-plane
// square), so that pdf(w) = p_texel / (A_texel rho(w)) with rho = (1 + sc^2 + tc^2)^(-3/2).
class EnvironmentSampler {
 public:
  explicit EnvironmentSampler(const std::array<Image, kFaceCount>& level);

  glm::vec3 radiance(glm::vec3 dir) const {
    const auto [face, x, y] = texelOf(dir);
    return level_[face].at(x, y);
  }

  float pdf(glm::vec3 dir) const {
    const auto [face, x, y] = texelOf(dir);
    const std::size_t i = (static_cast<std::size_t>(face) * n_ + y) * n_ + x;
    const double p = cdf_[i] - (i > 0 ? cdf_[i - 1] : 0.0);
    const FacePoint fp = directionToFace(dir);
    const float sc = 2.0f * fp.s - 1.0f, tc = 2.0f * fp.t - 1.0f;
    const float invRho = std::pow(1.0f + sc * sc + tc * tc, 1.5f);
    return static_cast<float>(p) * invRho / texelArea_;
  }

  glm::vec3 sample(glm::vec2 xi) const {
    const auto it = std::lower_bound(cdf_.begin(), cdf_.end(), static_cast<double>(xi.x));
    const auto i = static_cast<std::size_t>(
        std::min<std::ptrdiff_t>(it - cdf_.begin(), static_cast<std::ptrdiff_t>(cdf_.size()) - 1));
    const double lo = i > 0 ? cdf_[i - 1] : 0.0;
    // Reuse the position of xi.x within the texel's interval as the first coordinate.
    const float u =
        static_cast<float>(std::clamp((xi.x - lo) / std::max(cdf_[i] - lo, 1e-30), 0.0, 1.0));
    const int face = static_cast<int>(i / (static_cast<std::size_t>(n_) * n_));
    const int y = static_cast<int>(i / n_ % n_), x = static_cast<int>(i % n_);
    const float inv = 2.0f / static_cast<float>(n_);
    return glm::normalize(faceToDirection(face, (static_cast<float>(x) + u) * inv - 1.0f,
                                          (static_cast<float>(y) + xi.y) * inv - 1.0f));
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
  const std::array<Image, kFaceCount>& level_;
  int n_;
  std::vector<double> cdf_;
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

// Computes what tracePath reads once per process (the multiple-scattering table). Call it
// outside parallel work: a table built lazily inside a task could be re-entered by the same
// thread through oneTBB's work stealing.
void preparePathTracer();

// The radiance that surface point `p` at `position` sends toward unit direction `view` (its
// emission included): direct light from every light, the emissive triangles and the
// environment, and (up to options.bounces) the light other surfaces reflect. Unbiased but for the
// environment's texels.
glm::vec3 tracePath(const PathTracerScene& s, SurfacePoint p, glm::vec3 position, glm::vec3 view,
                    Random& rng);

// The nearest light the ray from p along w meets (lights do not hide one another beyond that):
// its index, or -1.
struct NearestLight {
  int index = -1;
  LightHit hit;
};
NearestLight nearestLight(const std::vector<Light>& lights, glm::vec3 p, glm::vec3 w);

}  // namespace ibl
