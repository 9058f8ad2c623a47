// Frostbite's approximations of ibl/shared/lights_frostbite.h against quadrature written here:
// illuminance of spheres and disks integrated over the light, and the solid angle of a rectangle.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "ibl/shared/lights_frostbite.h"
#include "support/numbers.hpp"
#include "support/quadrature.hpp"

namespace s = ibl::shared;

namespace {

using ibl::test::kPi;

using ibl::test::completeFrame;

// The midpoint rule in polar coordinates: the integral of f(rho, beta) over rho in [0, rhoMax]
// and beta in [0, 2 pi), n x n points.
template <typename F>
double integratePolar(double rhoMax, int n, const F& f) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) sum += f((i + 0.5) * rhoMax / n, (j + 0.5) * 2.0 * kPi / n);
  return sum * (rhoMax / n) * (2.0 * kPi / n);
}

// Illuminance from a spherical cap of luminance 1, half-angle sigma around `axis`, on a surface
// with normal n: the integral of max(0, n.w) dw over the cap (dw = sin(alpha) dalpha dbeta).
double capIlluminance(glm::dvec3 n, glm::dvec3 axis, double sigma) {
  glm::dvec3 t, b;
  completeFrame(axis, t, b);
  return integratePolar(sigma, 600, [&](double alpha, double beta) {
    const glm::dvec3 w =
        std::cos(alpha) * axis + std::sin(alpha) * (std::cos(beta) * t + std::sin(beta) * b);
    return std::max(0.0, glm::dot(n, w)) * std::sin(alpha);
  });
}

// Illuminance at the origin (normal n) from a one-sided disk of luminance 1, center c, radius r,
// emitting along m: the integral over its area of max(0, n.w) max(0, m.-w) / dist^2.
double diskIlluminance(glm::dvec3 n, glm::dvec3 c, double r, glm::dvec3 m) {
  glm::dvec3 u, v;
  completeFrame(m, u, v);
  return integratePolar(r, 400, [&](double rho, double beta) {
    const glm::dvec3 q = c + rho * (std::cos(beta) * u + std::sin(beta) * v);
    const double d2 = glm::dot(q, q);
    const glm::dvec3 w = q / std::sqrt(d2);
    return std::max(0.0, glm::dot(n, w)) * std::max(0.0, -glm::dot(m, w)) / d2 * rho;
  });
}

using ibl::test::direction;

}  // namespace

// Frostbite's sphere formula is exact: above, straddling and below the horizon, small to large.
TEST(Lights, SphereIlluminanceIsTheExactIntegral) {
  const glm::dvec3 n(0, 0, 1);
  for (double ratio : {0.05, 0.3, 0.6, 0.9})
    for (double theta : {0.0, 30.0, 60.0, 75.0, 90.0, 105.0, 120.0, 150.0}) {
      const double d = 2.0, r = ratio * d;
      const glm::dvec3 toLight = d * direction(theta);
      const double expected = capIlluminance(n, direction(theta), std::asin(ratio));
      const double got =
          s::sphereIlluminanceFactor(glm::vec3(n), glm::vec3(toLight), static_cast<float>(r));
      EXPECT_NEAR(got, expected, 2e-3 * kPi * ratio * ratio + 1e-6)
          << "r/d " << ratio << ", theta " << theta;
    }
}

// The disk is approximated: Frostbite treats it as a disk facing the point (which subtends a
// cap exactly: no error) and weights a tilted one by saturate(m . -l). Measured against
// quadrature over the disk, relative to the facing disk's on-axis value (pi r^2 / (r^2 + d^2)),
// over positions straddling the horizon and tilts of 30 and 60 degrees: exact when facing; for
// a small disk (r/d = 0.1) within 0.8 %; for r/d = 0.5 within 19 %, for r/d = 1 within 50 % (a
// disk as wide as its distance, tilted by 60 degrees, seen from its axis: the weight halves an
// illuminance that tilting leaves whole).
TEST(Lights, DiskIlluminanceApproximationIsMeasured) {
  const glm::dvec3 n(0, 0, 1);
  for (double ratio : {0.1, 0.5, 1.0}) {
    double worstFacing = 0.0, worstTilted = 0.0;
    for (double theta : {0.0, 40.0, 80.0, 95.0})
      for (double tilt : {0.0, 30.0, 60.0}) {
        const double d = 2.0, r = ratio * d;
        const glm::dvec3 c = d * direction(theta);
        // The disk faces the point, then turns by `tilt` about the y axis.
        const double a = tilt * kPi / 180.0;
        const glm::dvec3 facing = -glm::normalize(c);
        const glm::dvec3 m = glm::normalize(std::cos(a) * facing +
                                            std::sin(a) * glm::cross(glm::dvec3(0, 1, 0), facing));
        const double expected = diskIlluminance(n, c, r, m);
        const double got = s::diskIlluminanceFactor(glm::vec3(n), glm::vec3(c),
                                                    static_cast<float>(r), glm::vec3(m));
        const double error = std::abs(got - expected) / (kPi * r * r / (r * r + d * d));
        double& worst = tilt == 0.0 ? worstFacing : worstTilted;
        worst = std::max(worst, error);
      }
    EXPECT_LT(worstFacing, 2e-3) << ratio;
    EXPECT_LT(worstTilted, ratio < 0.2 ? 0.01 : ratio < 0.7 ? 0.2 : 0.51) << ratio;
  }
}
// The solid angle of a rectangle (its spherical quadrilateral's angle excess) is exact: against
// quadrature of (m.-w) / d^2 over the rectangle, from points in front at several offsets.
TEST(Lights, QuadSolidAngleIsExact) {
  const glm::dvec3 m(0, 0, -1), up(0, 1, 0), left = glm::cross(up, m);
  for (glm::dvec3 c : {glm::dvec3(0, 0, 1), glm::dvec3(0.7, -0.3, 0.5), glm::dvec3(2, 1, 0.4)}) {
    const double w = 1.2, h = 0.6;
    const auto q = [&](double u, double v) {
      return c + (u - 0.5) * w * left + (v - 0.5) * h * up;
    };
    double expected = 0.0;
    const int steps = 600;
    for (int i = 0; i < steps; ++i)
      for (int j = 0; j < steps; ++j) {
        const glm::dvec3 p = q((i + 0.5) / steps, (j + 0.5) / steps);
        const double d2 = glm::dot(p, p);
        expected += -glm::dot(m, p / std::sqrt(d2)) / d2 * w * h / (steps * steps);
      }
    const glm::vec3 cf(c), lf(left), uf(up);
    const float hw = 0.6f, hh = 0.3f;
    const double got = s::quadSolidAngle(cf - lf * hw + uf * hh, cf - lf * hw - uf * hh,
                                         cf + lf * hw - uf * hh, cf + lf * hw + uf * hh);
    EXPECT_NEAR(got, expected, 2e-4 * expected) << c.x;
  }
}
