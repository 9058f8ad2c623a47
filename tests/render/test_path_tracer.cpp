// The reference path tracer against closed forms: furnaces where every bounce is known.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "../../src/render/path_tracer.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/renderer.hpp"
#include "support/helpers.hpp"
#include "support/small_bake.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// A camera inside the closed sphere of radius 1 at the origin, looking at its wall.
Camera insideCamera() {
  Camera c;
  c.from = glm::vec3(0.2f, -0.1f, 0.3f);
  c.at = glm::vec3(0.0f, 0.0f, -1.0f);
  c.yfovDegrees = 60.0f;
  c.width = c.height = 4;
  return c;
}

}  // namespace

TEST(PathTracer, ClosedLambertianFurnace) {
  // Inside a closed sphere whose wall emits Le and reflects albedo a diffusely, the radiance is
  // the same everywhere: L = Le + a L, so L = Le / (1 - a). A path of N bounces sums the
  // emission, its direct light (one reflection) and N reflections more: the first N + 2 terms
  // of the series, Le (1 - a^(N+2)) / (1 - a), as for any light.
  BakeOptions bakeOptions;
  const BakeResult bake = smallBake(bakeOptions);
  Material wall;
  wall.baseColor = glm::vec3(0.6f);
  wall.metallic = 0.0f;
  wall.specular = 0.0f;  // Lambertian: no layer takes a share (fresnel_mix)
  wall.emissive = glm::vec3(1.0f, 0.5f, 0.25f);
  Scene scene;
  scene.materials.push_back(wall);
  scene.spheres.push_back({glm::vec3(0.0f), 1.0f, 0});
  RenderOptions o;
  o.mode = RenderMode::Reference;
  o.diffuse = DiffuseModel::Lambert;
  o.only = ShadingTerms::Diffuse;
  o.environmentLight = false;
  o.spp = 4096;
  o.shadows = true;  // traced visibility, so that bounces 0 sees the wall's direct light too
  const float a = 0.6f;
  for (int bounces : {0, 1, 3, 40}) {
    o.bounces = bounces;
    const RenderResult r = renderScene(scene, insideCamera(), bake, bakeOptions, o);
    const glm::vec3 expected =
        wall.emissive * ((1.0f - std::pow(a, static_cast<float>(bounces + 2))) / (1.0f - a));
    glm::vec3 mean(0.0f);
    for (const glm::vec3& c : r.color.pixels) mean += c / static_cast<float>(r.color.pixels.size());
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(mean[c] / expected[c], 1.0f, 0.01f) << "bounces " << bounces << " channel " << c;
  }
}

namespace {

// A patch of a box wall: corner, edges, inward normal, and what it emits and reflects.
struct WallPatch {
  glm::vec3 corner, u, v, normal;
  glm::vec3 emission, albedo;
  float area() const { return glm::length(glm::cross(u, v)); }
};

}  // namespace

TEST(PathTracer, CornellBoxAgreesWithRadiosity) {
  // A closed unit box of Lambertian walls (red left, green right, white elsewhere) lit by an
  // emitting ceiling (all but its border). The independent estimate is classical radiosity (Goral
  // et al. 1984): the walls cut into 8 x 8 patches, form factors by 4 x 4-point quadrature of cos
  // cos / (pi r^2) between patches, B = pi Le + rho F B solved by iteration; a patch's radiance is
  // B / pi. The path tracer (50 bounces) is read as the mean luminance over each of the patches
  // away from the walls' edges (where constant patches and the form factor kernel's singularity
  // make radiosity itself inexact).
  constexpr int n = 8, q = 4;
  const glm::vec3 white(0.73f), red(0.63f, 0.065f, 0.05f), green(0.14f, 0.45f, 0.09f);
  const glm::vec3 le(1.0f);
  std::vector<WallPatch> patches;
  Scene scene;
  const glm::vec3 center(0.5f);
  for (int wall = 0; wall < 6; ++wall) {
    const int axis = wall / 2;
    const bool high = wall % 2 == 1;
    glm::vec3 origin(0.0f), u(0.0f), v(0.0f);
    if (high) origin[axis] = 1.0f;
    u[(axis + 1) % 3] = 1.0f / n;
    v[(axis + 2) % 3] = 1.0f / n;
    glm::vec3 normal(0.0f);
    normal[axis] = high ? -1.0f : 1.0f;
    const glm::vec3 albedo = wall == 0 ? red : (wall == 1 ? green : white);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        // The ceiling (+Y) emits but for its outer ring of patches.
        const bool lamp = wall == 3 && i > 0 && i < n - 1 && j > 0 && j < n - 1;
        WallPatch p{origin + static_cast<float>(i) * u + static_cast<float>(j) * v,
                    u,
                    v,
                    normal,
                    lamp ? le : glm::vec3(0.0f),
                    albedo};
        patches.push_back(p);
        Material m;
        m.baseColor = albedo;
        m.metallic = 0.0f;
        m.specular = 0.0f;  // Lambertian patches, as radiosity has them
        m.emissive = p.emission;
        scene.materials.push_back(m);
        Mesh mesh;
        mesh.positions = {p.corner, p.corner + u, p.corner + u + v, p.corner + v};
        mesh.normals.assign(4, normal);
        const bool facing = glm::dot(glm::cross(u, v), normal) > 0.0f;
        mesh.indices = facing ? std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}
                              : std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2};
        mesh.material = static_cast<int>(scene.materials.size()) - 1;
        scene.meshes.push_back(std::move(mesh));
      }
  }
  // Radiosity.
  const std::size_t count = patches.size();
  std::vector<float> form(count * count, 0.0f);
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t j = 0; j < count; ++j) {
      if (i == j || patches[i].normal == patches[j].normal) continue;  // coplanar: 0
      const WallPatch &a = patches[i], &b = patches[j];
      double sum = 0.0;
      for (int s = 0; s < q * q; ++s)
        for (int t = 0; t < q * q; ++t) {
          const glm::vec3 x = a.corner + ((s % q + 0.5f) / q) * a.u + ((s / q + 0.5f) / q) * a.v;
          const glm::vec3 y = b.corner + ((t % q + 0.5f) / q) * b.u + ((t / q + 0.5f) / q) * b.v;
          const glm::vec3 d = y - x;
          const float r2 = glm::dot(d, d);
          const float ci = glm::dot(a.normal, d), cj = -glm::dot(b.normal, d);
          if (ci > 0.0f && cj > 0.0f) sum += ci * cj / (std::numbers::pi * r2 * r2);
        }
      // F_ij = (1 / A_i) integral over both patches: mean kernel x A_j.
      form[i * count + j] = static_cast<float>(sum / (q * q * q * q) * b.area());
    }
  std::vector<glm::vec3> radiosity(count);
  for (std::size_t i = 0; i < count; ++i)
    radiosity[i] = std::numbers::pi_v<float> * patches[i].emission;
  for (int iteration = 0; iteration < 200; ++iteration) {
    std::vector<glm::vec3> next(count);
    for (std::size_t i = 0; i < count; ++i) {
      glm::vec3 gathered(0.0f);
      for (std::size_t j = 0; j < count; ++j) gathered += form[i * count + j] * radiosity[j];
      next[i] = std::numbers::pi_v<float> * patches[i].emission + patches[i].albedo * gathered;
    }
    radiosity = next;
  }
  // The path tracer: one pixel per patch, its rays from the box's center through points spread
  // over the patch.
  BakeOptions bakeOptions;
  const BakeResult bake = smallBake(bakeOptions);
  RenderOptions o;
  o.mode = RenderMode::Reference;
  o.diffuse = DiffuseModel::Lambert;
  o.only = ShadingTerms::Diffuse;
  o.environmentLight = false;
  o.bounces = 50;
  o.spp = 4096;
  const RenderResult traced = renderRays(
      scene, static_cast<int>(count), 1,
      [&](glm::vec2 pixel) {
        const WallPatch& p = patches[std::min(static_cast<std::size_t>(pixel.x), count - 1)];
        const float fu = pixel.x - std::floor(pixel.x), fv = pixel.y - std::floor(pixel.y);
        return Ray{center, glm::normalize(p.corner + fu * p.u + fv * p.v - center)};
      },
      bake, bakeOptions, o);
  double worst = 0.0, mean = 0.0, squares = 0.0;
  int compared = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const int a = static_cast<int>(i % (n * n)) / n, b = static_cast<int>(i % n);
    if (a < 2 || a > n - 3 || b < 2 || b > n - 3 || patches[i].emission != glm::vec3(0.0f))
      continue;
    const glm::vec3 expected = radiosity[i] / std::numbers::pi_v<float>;
    const glm::vec3 got = traced.color.at(static_cast<int>(i), 0);
    const double ratio = luminance(got) / luminance(expected);
    worst = std::max(worst, std::abs(ratio - 1.0));
    mean += ratio;
    squares += (ratio - 1.0) * (ratio - 1.0);
    ++compared;
  }
  mean /= compared;
  const double rms = std::sqrt(squares / compared);
  std::printf(
      "Cornell box, path tracer / radiosity over %d patches: mean %.4f, rms %.4f, worst "
      "%.4f\n",
      compared, mean, rms, worst);
  // Measured: mean 0.998, rms 0.035 (the path tracer's noise at 4096 paths per patch), worst 0.11.
  EXPECT_NEAR(mean, 1.0, 0.015);
  EXPECT_LT(rms, 0.05);
  EXPECT_LT(worst, 0.15);
}

// The reference's environment sampling against its own density: pdf() integrates to 1 over the
// sphere (a midpoint rule over 8 x 8 cells per texel, each cell's solid angle from the corners'
// closed form, written here), and the share of samples that land in each quarter of each texel
// is that integral over the quarter, for independent uniform numbers, within 5 standard errors
// (the quarters see where in its texel a sample lands, not only which texel).
TEST(PathTracer, EnvironmentSamplesFollowTheirDensity) {
  const int n = 8;
  std::array<Image, kFaceCount> level;
  for (int f = 0; f < kFaceCount; ++f) {
    level[f] = Image(n, n);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)  // a gradient, dark texels and one bright texel
        level[f].at(x, y) = glm::vec3(0.1f * static_cast<float>(f + x) *
                                      static_cast<float>((x + y) % 3 == 0 ? 0 : 1)) +
                            glm::vec3(f == 2 && x == 5 && y == 1 ? 500.0f : 0.0f);
  }
  const EnvironmentSampler sampler(level);
  // Solid angle of the face-plane square [a0, a1] x [b0, b1] at unit distance: the difference
  // of atan(a b / sqrt(1 + a^2 + b^2)) over its corners.
  const auto cornerTerm = [](double a, double b) {
    return std::atan2(a * b, std::sqrt(1.0 + a * a + b * b));
  };
  const auto squareSolidAngle = [&](double a0, double a1, double b0, double b1) {
    return cornerTerm(a1, b1) - cornerTerm(a0, b1) - cornerTerm(a1, b0) + cornerTerm(a0, b0);
  };
  const int sub = 8, bins = 2 * n;  // quadrature cells per texel side; bins per face side
  const auto bin = [&](int f, int x, int y) {
    return (static_cast<std::size_t>(f) * bins + y) * bins + x;
  };
  std::vector<double> expected(static_cast<std::size_t>(kFaceCount) * bins * bins, 0.0);
  double total = 0.0;
  for (int f = 0; f < kFaceCount; ++f)
    for (int y = 0; y < n * sub; ++y)
      for (int x = 0; x < n * sub; ++x) {
        const double a0 = 2.0 * x / (n * sub) - 1.0, a1 = 2.0 * (x + 1) / (n * sub) - 1.0;
        const double b0 = 2.0 * y / (n * sub) - 1.0, b1 = 2.0 * (y + 1) / (n * sub) - 1.0;
        const glm::vec3 w = glm::normalize(faceToDirection(f, static_cast<float>(0.5 * (a0 + a1)),
                                                           static_cast<float>(0.5 * (b0 + b1))));
        const double p = sampler.pdf(w) * squareSolidAngle(a0, a1, b0, b1);
        expected[bin(f, x * bins / (n * sub), y * bins / (n * sub))] += p;
        total += p;
      }
  EXPECT_NEAR(total, 1.0, 2e-3);
  std::vector<double> counts(expected.size(), 0.0);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const int samples = 1 << 21;
  for (int i = 0; i < samples; ++i) {
    const FacePoint p = directionToFace(sampler.sample({u(rng), u(rng)}));
    counts[bin(p.face, std::clamp(static_cast<int>(p.s * bins), 0, bins - 1),
               std::clamp(static_cast<int>(p.t * bins), 0, bins - 1))] += 1.0;
  }
  for (std::size_t b = 0; b < counts.size(); ++b) {
    const double share = counts[b] / samples, p = expected[b];
    EXPECT_NEAR(share, p, 5.0 * std::sqrt(p * (1.0 - p) / samples) + 2e-4 * p) << "bin " << b;
  }
}
