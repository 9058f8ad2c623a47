// The reference's light sampling (ibl/render/light_sampling.hpp) against quadrature written
// here: the illuminance a point receives from each area light, integrated over the light's
// surface by the midpoint rule, equals both Monte Carlo estimates (sampling the light, and
// sampling the cosine lobe and meeting the light by intersection); each sampler's density
// integrates to one over the sphere of directions.
#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/math/sampling.hpp"
#include "ibl/render/light_sampling.hpp"
#include "support/numbers.hpp"
#include "support/quadrature.hpp"

using namespace ibl;

namespace {

using ibl::test::kPi;

using ibl::test::completeFrame;

// A patch of surface: position and unit normal at (u, v) in [0, 1]^2, and the area element.
struct Patch {
  std::function<glm::dvec3(double, double)> position;
  std::function<glm::dvec3(double, double)> normal;
  std::function<double(double, double)> jacobian;
};

// The illuminance at p (normal n) from the patches of luminance 1 that face p (the emitter is
// convex, so those are the ones p sees): the integral of cos_p cos_light / d^2 dA.
double illuminanceByQuadrature(const std::vector<Patch>& patches, glm::dvec3 p, glm::dvec3 n,
                               int steps = 600) {
  double sum = 0.0;
  for (const Patch& patch : patches)
    for (int i = 0; i < steps; ++i)
      for (int j = 0; j < steps; ++j) {
        const double u = (i + 0.5) / steps, v = (j + 0.5) / steps;
        const glm::dvec3 d = patch.position(u, v) - p;
        const double d2 = glm::dot(d, d);
        const glm::dvec3 w = d / std::sqrt(d2);
        const double cosLight = -glm::dot(patch.normal(u, v), w);
        if (cosLight <= 0.0) continue;
        sum += std::max(0.0, glm::dot(n, w)) * cosLight / d2 * patch.jacobian(u, v) /
               (static_cast<double>(steps) * steps);
      }
  return sum;
}

// A sphere (or a hemisphere: vMax = 0.5) of radius r around c, axis a.
Patch spherePatch(glm::dvec3 c, double r, glm::dvec3 a, double vFrom, double vTo) {
  glm::dvec3 t, b;
  completeFrame(a, t, b);
  const auto dir = [=](double u, double v) {
    const double theta = (vFrom + (vTo - vFrom) * v) * kPi, phi = 2.0 * kPi * u;
    return std::cos(theta) * a + std::sin(theta) * (std::cos(phi) * t + std::sin(phi) * b);
  };
  return {[=](double u, double v) { return c + r * dir(u, v); }, dir,
          [=](double, double v) {
            return r * r * std::sin((vFrom + (vTo - vFrom) * v) * kPi) * 2.0 * kPi * kPi *
                   (vTo - vFrom);
          }};
}

std::vector<Patch> patchesOf(const Light& l) {
  const glm::dvec3 c(l.position), m(l.direction);
  switch (l.type) {
    case LightType::Sphere:
      return {spherePatch(c, l.radius, m, 0.0, 1.0)};
    case LightType::Disk: {
      glm::dvec3 t, b;
      completeFrame(m, t, b);
      const double r = l.radius;
      return {{[=](double u, double v) {
                 const double rho = r * v, phi = 2.0 * kPi * u;
                 return c + rho * (std::cos(phi) * t + std::sin(phi) * b);
               },
               [=](double, double) { return m; },
               [=](double, double v) { return r * v * r * 2.0 * kPi; }}};
    }
    case LightType::Rect: {
      const glm::dvec3 up(l.up), left = glm::cross(up, m);
      const double w = l.width, h = l.height;
      return {{[=](double u, double v) { return c + (u - 0.5) * w * left + (v - 0.5) * h * up; },
               [=](double, double) { return m; }, [=](double, double) { return w * h; }}};
    }
    case LightType::Tube: {
      glm::dvec3 t, b;
      completeFrame(m, t, b);
      const double r = l.radius, len = l.length;
      Patch cylinder{[=](double u, double v) {
                       const double phi = 2.0 * kPi * u;
                       return c + (v - 0.5) * len * m + r * (std::cos(phi) * t + std::sin(phi) * b);
                     },
                     [=](double u, double) {
                       const double phi = 2.0 * kPi * u;
                       return std::cos(phi) * t + std::sin(phi) * b;
                     },
                     [=](double, double) { return 2.0 * kPi * r * len; }};
      return {cylinder, spherePatch(c + 0.5 * len * m, r, m, 0.0, 0.5),
              spherePatch(c - 0.5 * len * m, r, m, 0.5, 1.0)};
    }
    default:
      return {};
  }
}

Light areaLight(LightType type) {
  Light l;
  l.type = type;
  l.name = "test light";
  l.intensity = 1.0f;
  l.position = glm::vec3(0.3f, 1.2f, -0.2f);
  l.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.3f));
  l.up = glm::normalize(glm::cross(l.direction, glm::vec3(1, 0, 0)));
  l.radius = 0.4f;
  l.width = 1.2f;
  l.height = 0.5f;
  l.length = 1.5f;
  if (type == LightType::Tube) l.radius = 0.15f;
  checkLight(l);
  return l;
}

struct Estimates {
  double lightSampling, brdfSampling;
};

// The illuminance at p (normal n) by sampling the light, and by sampling the cosine lobe.
Estimates illuminanceByMonteCarlo(const Light& l, glm::vec3 p, glm::vec3 n, int count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  double a = 0.0, b = 0.0;
  const glm::mat3 f = tangentFrame(n);
  for (int i = 0; i < count; ++i) {
    const LightSample s = sampleLight(l, p, {u(rng), u(rng)});
    if (s.pdf > 0.0f) a += s.radiance.x * std::max(0.0f, glm::dot(n, s.direction)) / s.pdf;
    const glm::vec3 w = f * sampleCosineHemisphere({u(rng), u(rng)});
    if (const auto hit = intersectLight(l, p, w)) b += kPi * hit->radiance.x;
  }
  return {a / count, b / count};
}

}  // namespace

// Each area light, seen from points in front, beside and straddling its horizon.
TEST(LightSampling, IlluminanceMatchesQuadratureOverTheLight) {
  const glm::vec3 points[] = {{0, 0, 0}, {1.5f, 0.4f, 0.5f}, {0.2f, 1.1f, 1.4f}};
  const glm::vec3 normals[] = {
      {0, 1, 0}, glm::normalize(glm::vec3(-1, 0.3f, 0)), glm::normalize(glm::vec3(0.3f, 0.1f, -1))};
  for (LightType type : {LightType::Sphere, LightType::Disk, LightType::Rect, LightType::Tube}) {
    const Light l = areaLight(type);
    for (int k = 0; k < 3; ++k) {
      const double expected = illuminanceByQuadrature(patchesOf(l), points[k], normals[k]);
      const Estimates e = illuminanceByMonteCarlo(l, points[k], normals[k], 200000);
      const double tolerance = 0.01 * expected + 1e-4;
      EXPECT_NEAR(e.lightSampling, expected, tolerance)
          << lightTypeName(type) << " light sampling, point " << k;
      EXPECT_NEAR(e.brdfSampling, expected, 3.0 * tolerance)
          << lightTypeName(type) << " cosine sampling, point " << k;
    }
  }
}

// The sun: E lux on a surface facing it, E cos(theta) on a tilted one (its cap is tiny).
TEST(LightSampling, SunDeliversItsIlluminance) {
  Light sun;
  sun.type = LightType::Sun;
  sun.direction = glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
  sun.intensity = 1000.0f;
  sun.angularDiameter = 0.2f;  // large, so the cap's integral is tested
  for (float tilt : {0.0f, 0.6f, 1.2f}) {
    const glm::vec3 n = glm::normalize(sun.direction + tilt * glm::vec3(1, 0, -1));
    const Estimates e = illuminanceByMonteCarlo(sun, glm::vec3(0.0f), n, 100000);
    // The cap is within the hemisphere: E = L pi sin^2(sigma) x cos(angle to its axis) exactly.
    const double expected = 1000.0 * glm::dot(n, sun.direction);
    EXPECT_NEAR(e.lightSampling, expected, 1e-3 * expected) << tilt;
  }
}

// The sampled density is the density lightPdf gives that direction, and it integrates to 1 over
// all directions (uniform sphere sampling of lightPdf), for lights every sample reaches.
TEST(LightSampling, DensitiesAgreeAndIntegrateToOne) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const glm::vec3 p(0.1f, -0.5f, 0.2f);
  for (LightType type : {LightType::Sphere, LightType::Disk, LightType::Rect}) {
    const Light l = areaLight(type);
    for (int i = 0; i < 200; ++i) {
      const LightSample s = sampleLight(l, p, {u(rng), u(rng)});
      ASSERT_GT(s.pdf, 0.0f);
      EXPECT_NEAR(lightPdf(l, p, s.direction), s.pdf, 2e-3f * s.pdf) << lightTypeName(type);
    }
    double integral = 0.0;
    const int n = 2000000;
    for (int i = 0; i < n; ++i) {
      const float z = 1.0f - 2.0f * u(rng), phi = 2.0f * static_cast<float>(kPi) * u(rng);
      const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
      integral += lightPdf(l, p, {r * std::cos(phi), r * std::sin(phi), z});
    }
    EXPECT_NEAR(integral * 4.0 * kPi / n, 1.0, 0.02) << lightTypeName(type);
  }
}
