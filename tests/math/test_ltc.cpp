// Linearly transformed cosines (ibl/shared/ltc.h, ibl/render/ltc.hpp) against quadrature written
// here: the clipped polygon's form factor against the cosine integrated over the light, the
// table's GGX lobe over rects and disks against the BRDF integrated over them, and the table
// against the fitter that wrote it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "ibl/render/ltc.hpp"
#include "ibl/shared/brdf.h"
#include "ibl/shared/lights.h"
#include "ibl/shared/ltc.h"
#include "support/quadrature.hpp"

namespace s = ibl::shared;
using ibl::test::completeFrame;
using ibl::test::integrateOverPatch;

namespace {

constexpr double kPi = std::numbers::pi;
const glm::vec4 kCosine(1.0f, 0.0f, 0.0f, 1.0f);

// A rect centered at c (relative to the shaded point), emitting along m, of w x h.
struct Rect {
  glm::dvec3 c, m, up;
  double w, h;
  [[nodiscard]] glm::dvec3 left() const { return glm::cross(up, m); }
  [[nodiscard]] glm::dvec3 at(double u, double v) const {
    return c + (u - 0.5) * w * left() + (v - 0.5) * h * up;
  }
  [[nodiscard]] glm::vec3 corner(int i) const {
    return glm::vec3(at(i < 2 ? 0.0 : 1.0, i == 0 || i == 3 ? 1.0 : 0.0));
  }
  template <typename F>
  [[nodiscard]] double integrate(const F& f, int steps = 500) const {
    return integrateOverPatch(
        f, [&](double u, double v) { return at(u, v); }, [&](double, double) { return m; },
        [&](double, double) { return w * h; }, steps);
  }
};

// A rect facing the point from direction `dir` at distance d, turned by `tilt` radians.
Rect rectToward(glm::dvec3 dir, double d, double tilt, double w, double h) {
  glm::dvec3 t, b;
  completeFrame(dir, t, b);
  const glm::dvec3 m = glm::normalize(-std::cos(tilt) * dir + std::sin(tilt) * t);
  return Rect{d * dir, m, glm::normalize(glm::cross(m, t)), w, h};
}

glm::dvec3 direction(double thetaDegrees, double phiDegrees) {
  const double t = thetaDegrees * kPi / 180.0, p = phiDegrees * kPi / 180.0;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// The GGX lobe times the cosine (no Fresnel) at the origin, normal +z, view v, in double.
double ggxLobe(glm::dvec3 v, glm::dvec3 l, double alpha) {
  if (l.z <= 0.0) return 0.0;
  const glm::dvec3 h = glm::normalize(v + l);
  const double a2 = alpha * alpha, d = h.z * h.z * (a2 - 1.0) + 1.0;
  const double lambdaV = l.z * std::sqrt(v.z * v.z * (1.0 - a2) + a2);
  const double lambdaL = v.z * std::sqrt(l.z * l.z * (1.0 - a2) + a2);
  return a2 / (kPi * d * d) * 0.5 / (lambdaV + lambdaL) * l.z;
}

// The integral of f(l) over the hemisphere (midpoint rule in cos theta and phi).
template <typename F>
double overHemisphere(const F& f, int n = 1500) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    // cos theta = 1 - x^2 puts the points close together near the normal, where the lobe is.
    const double x = (i + 0.5) / n, c = 1.0 - x * x, sn = std::sqrt(1.0 - c * c);
    for (int j = 0; j < n; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / n;
      sum += f(glm::dvec3(sn * std::cos(phi), sn * std::sin(phi), c)) * 2.0 * x;
    }
  }
  return sum * (1.0 / n) * (2.0 * kPi / n);
}

// The lobe's integral over the hemisphere.
double ggxAlbedo(glm::dvec3 v, double alpha) {
  return overHemisphere([&](glm::dvec3 l) { return ggxLobe(v, l, alpha); });
}

// The integral of f over the surface of the capsule (segment c +- hl d, radius r) seen from the
// origin, f(l) times the cosine at the light over the squared distance (the solid angle's
// measure), over the points that face the origin (all visible: the capsule is convex): midpoint
// rule over the cylinder (4n x 2n) and each hemispherical cap (n x 2n, equal steps of z).
template <typename F>
double overCapsule(glm::dvec3 c, glm::dvec3 d, double hl, double r, const F& f, int n = 200) {
  glm::dvec3 t, b;
  completeFrame(d, t, b);
  double sum = 0.0;
  const auto add = [&](glm::dvec3 x, glm::dvec3 m, double area) {
    const double d2 = glm::dot(x, x);
    const glm::dvec3 l = x / std::sqrt(d2);
    const double cosLight = -glm::dot(m, l);
    if (cosLight > 0.0) sum += f(l) * cosLight / d2 * area;
  };
  const int na = 4 * n, nphi = 2 * n;
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nphi; ++j) {
      const double along = -hl + 2.0 * hl * (i + 0.5) / na, phi = 2.0 * kPi * (j + 0.5) / nphi;
      const glm::dvec3 m = std::cos(phi) * t + std::sin(phi) * b;
      add(c + along * d + r * m, m, 2.0 * kPi * r * 2.0 * hl / (na * nphi));
    }
  for (double side : {-1.0, 1.0})
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < nphi; ++j) {
        const double z = (i + 0.5) / n, sn = std::sqrt(1.0 - z * z);
        const double phi = 2.0 * kPi * (j + 0.5) / nphi;
        const glm::dvec3 m = side * (z * d + sn * (std::cos(phi) * t + std::sin(phi) * b));
        add(c + side * hl * d + r * m, m, 2.0 * kPi * r * r / (n * nphi));
      }
  return sum;
}

}  // namespace

// With the cosine itself (the identity entry) the clipped polygon's vector is the irradiance
// vector of Arvo 1995, (1 / pi) times the integral of w over the polygon's part above the
// horizon: its z is Lambert's form factor. Against quadrature over rects in front of, beside and
// straddling the horizon.
TEST(Ltc, PolygonFormFactorIsExact) {
  for (double theta : {0.0, 40.0, 75.0, 90.0, 105.0})
    for (double tilt : {0.0, 0.6}) {
      const Rect r = rectToward(direction(theta, 30.0), 1.5, tilt, 1.2, 0.7);
      const s::LtcFrame f = s::ltcFrame(glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), kCosine);
      const glm::vec3 got = s::ltcFrameToWorld(
          f, s::ltcQuadIntegral(f, r.corner(0), r.corner(1), r.corner(2), r.corner(3)));
      for (int k = 0; k < 3; ++k) {
        const double expected =
            r.integrate([&](glm::dvec3 w) { return w.z > 0.0 ? w[k] : 0.0; }) / kPi;
        EXPECT_NEAR(got[k], expected, 2e-5) << theta << " " << tilt << " " << k;
      }
    }
}

// The table's LTC of GGX against the lobe integrated over rects (no Fresnel, normalized by the
// lobe's integral over the hemisphere): rects at the mirror direction, beside it, and straddling
// the horizon, at roughness and n.v on and between the table's entries. The error is the
// difference of the fractions of the lobe the rect covers.
TEST(Ltc, TableMatchesTheGgxLobeOverRects) {
  double worst = 0.0, worstRelative = 0.0;
  for (double roughness : {0.3, 0.45, 0.8})
    for (double NoV : {0.95, 0.7, 0.4}) {
      const double alpha = roughness * roughness;
      const glm::dvec3 v(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
      const double albedo = ggxAlbedo(v, alpha);
      const glm::vec4 entry =
          ibl::ltcTableLookup(static_cast<float>(roughness), static_cast<float>(NoV));
      const s::LtcFrame f = s::ltcFrame(glm::vec3(0, 0, 1), glm::vec3(v), entry);
      const glm::dvec3 mirror(-v.x, 0.0, v.z);
      for (glm::dvec3 dir :
           {mirror, glm::normalize(mirror + glm::dvec3(0.0, 0.5, 0.2)), direction(85.0, 150.0)}) {
        const Rect r = rectToward(dir, 2.0, 0.3, 1.0, 0.6);
        const double expected =
            r.integrate([&](glm::dvec3 w) { return ggxLobe(v, w, alpha); }) / albedo;
        const double got =
            s::ltcQuadIntegral(f, r.corner(0), r.corner(1), r.corner(2), r.corner(3)).z;
        worst = std::max(worst, std::abs(got - expected));
        if (expected > 0.05)
          worstRelative = std::max(worstRelative, std::abs(got - expected) / expected);
      }
    }
  // Measured 0.0205, and 18.7 % where the rect holds over 5 % of the lobe (the table fitted with
  // the cube of the difference, Heitz's objective: 0.0091 and 8.2 %; the first power, shipped,
  // trades these rects near the peak for the tails: docs/lights.md, "The LTC table and its fit").
  EXPECT_LT(worst, 0.025);
  EXPECT_LT(worstRelative, 0.22);
}

// The table's lobe in its tails: a disk (radius 0.15 at 2 m, 0.075 rad) off the mirror direction
// by 0.35 to 0.9 rad, in the plane of incidence (toward the normal and toward the horizon) and
// across it, at roughness 0.5 and 0.75 and n.v 0.9 and 0.5 (between the table's entries), against
// the lobe integrated over the disk here; where the disk holds at least 1/1000 of the lobe's
// peak disk's (the same disk at the mirror direction). The error is the ratio LTC / GGX.
TEST(Ltc, TableHoldsTheLobesTails) {
  double worstLow = 1.0, worstHigh = 1.0;
  for (double roughness : {0.5, 0.75})
    for (double NoV : {0.9, 0.5}) {
      const double alpha = roughness * roughness;
      const glm::dvec3 v(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
      const double albedo = ggxAlbedo(v, alpha);
      const s::LtcFrame f =
          s::ltcFrame(glm::vec3(0, 0, 1), glm::vec3(v),
                      ibl::ltcTableLookup(static_cast<float>(roughness), static_cast<float>(NoV)));
      const glm::dvec3 mirror(-v.x, 0.0, v.z);
      const double mirrorTheta = std::acos(mirror.z);
      const auto diskAt = [&](glm::dvec3 dir, double& got) {
        glm::dvec3 u, w;
        completeFrame(dir, u, w);
        const double radius = 0.15, d = 2.0;
        const int n = 200;
        double sum = 0.0;
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) {
            const double rho = radius * std::sqrt((i + 0.5) / n), beta = 2.0 * kPi * (j + 0.5) / n;
            const glm::dvec3 q = d * dir + rho * (std::cos(beta) * u + std::sin(beta) * w);
            const double d2 = glm::dot(q, q);
            const glm::dvec3 l = q / std::sqrt(d2);
            sum += ggxLobe(v, l, alpha) * std::abs(glm::dot(dir, l)) / d2;
          }
        got = s::ltcDiskIntegral(f, glm::vec3(d * dir), glm::vec3(u), glm::vec3(w),
                                 static_cast<float>(radius))
                  .z;
        return sum * kPi * radius * radius / (n * n) / albedo;
      };
      double peakGot = 0.0;
      const double peak = diskAt(mirror, peakGot);
      for (double offset : {0.35, 0.6, 0.9})
        for (int way = 0; way < 3; ++way) {
          glm::dvec3 dir;
          if (way == 2) {
            dir = glm::normalize(mirror + offset * glm::dvec3(0.0, 1.0, 0.0));
          } else {
            const double theta = mirrorTheta + (way == 0 ? -offset : offset);
            if (theta > 1.45) continue;  // below the horizon
            dir = theta >= 0.0 ? glm::dvec3(-std::sin(theta), 0.0, std::cos(theta))
                               : glm::dvec3(std::sin(-theta), 0.0, std::cos(theta));
          }
          double got = 0.0;
          const double expected = diskAt(dir, got);
          if (expected < 1e-3 * peak) continue;
          const double ratio = got / expected;
          std::printf(
              "roughness %.2f n.v %.2f offset %.2f way %d: %.2e of the peak, LTC / GGX %.3f\n",
              roughness, NoV, offset, way, expected / peak, ratio);
          worstLow = std::min(worstLow, ratio);
          worstHigh = std::max(worstHigh, ratio);
        }
    }
  std::printf("tails: LTC / GGX from %.3f to %.3f\n", worstLow, worstHigh);
  // Measured 0.627 (n.v 0.5, 0.35 rad toward the horizon) to 1.141 (n.v 0.5, 0.9 rad toward
  // the normal), down to 2e-2 of the peak's disk.
  EXPECT_GT(worstLow, 0.55);
  EXPECT_LT(worstHigh, 1.25);
}

// The disk as its equal-area 16-gon and the sphere as the disk facing the point: their cosine
// integrals against quadrature over the disk and the exact sphere formula (lights.h, itself
// tested against quadrature in test_lights.cpp), in front and straddling the horizon.
TEST(Ltc, DiskAndSphereAsPolygonsAreMeasured) {
  const s::LtcFrame f = s::ltcFrame(glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), kCosine);
  double worstDisk = 0.0, worstSphere = 0.0;
  for (double theta : {0.0, 50.0, 85.0, 95.0})
    for (double tilt : {0.0, 0.7}) {
      const glm::dvec3 dir = direction(theta, 20.0);
      glm::dvec3 t, b;
      completeFrame(dir, t, b);
      const glm::dvec3 m = glm::normalize(-std::cos(tilt) * dir + std::sin(tilt) * t);
      glm::dvec3 u, w;
      completeFrame(m, u, w);
      const double radius = 0.6, d = 1.5;
      const glm::dvec3 c = d * dir;
      const int n = 400;
      double expected = 0.0;  // polar midpoint rule over the disk
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const double rho = (i + 0.5) * radius / n, beta = (j + 0.5) * 2.0 * kPi / n;
          const glm::dvec3 q = c + rho * (std::cos(beta) * u + std::sin(beta) * w);
          const double d2 = glm::dot(q, q);
          const glm::dvec3 l = q / std::sqrt(d2);
          expected += std::max(0.0, l.z) * std::max(0.0, -glm::dot(m, l)) / d2 * rho;
        }
      expected *= (radius / n) * (2.0 * kPi / n) / kPi;
      const double facing = radius * radius / (radius * radius + d * d);  // the disk facing +z
      const double disk = s::ltcDiskIntegral(f, glm::vec3(c), glm::vec3(u), glm::vec3(w),
                                             static_cast<float>(radius))
                              .z;
      worstDisk = std::max(worstDisk, std::abs(disk - expected) / facing);
      const double sphere = s::ltcSphereIntegral(f, glm::vec3(c), static_cast<float>(radius)).z;
      const double exact =
          s::sphereIlluminanceFactor(glm::vec3(0, 0, 1), glm::vec3(c), static_cast<float>(radius)) /
          kPi;
      worstSphere = std::max(worstSphere, std::abs(sphere - exact) / (radius * radius / (d * d)));
    }
  EXPECT_LT(worstDisk, 2e-4);    // measured 0.0017 % of the facing disk's
  EXPECT_LT(worstSphere, 2e-4);  // 0.0018 % of the sphere's r^2 / d^2
}

// The tube's capsule as the polygon of its silhouette (lights.h, ltcCapsuleIntegral), integrated
// through the LTC's clipped polygon, against the LTC's density integrated over the capsule's
// surface: the cosine itself (Lambert's form factor) and a GGX entry of the table, capsules
// broadside, turned, nearly end-on and of length 0 (a sphere), in front of the point, beside and
// straddling its horizon. Measured: within 0.3 % where the capsule holds over 1e-3 of the
// lobe (the caps' arcs as polygons); Frostbite's split (the facing rect plus one sphere at the
// segment's nearest point, the former rule) is 21 % off broadside at 1.2 m, and the caps' arcs
// taken on the wrong side of their circles 21 % to 99 %.
TEST(Ltc, CapsulePolygonMatchesQuadratureOverTheCapsule) {
  double worst = 0.0;
  const glm::vec3 v = glm::normalize(glm::vec3(0.6f, 0.0f, 0.8f));
  for (glm::vec4 entry :
       {kCosine, ibl::ltcTableLookup(0.5f, 0.8f), ibl::ltcTableLookup(0.3f, 0.5f)})
    for (double theta : {0.0, 40.0, 80.0, 95.0})
      for (double turn : {0.0, 0.7, 1.4})
        for (double hl : {0.75, 0.0}) {
          const double t = theta * kPi / 180.0;
          const glm::dvec3 dir =
              glm::normalize(glm::dvec3(std::sin(t), 0.3 * std::sin(t), std::cos(t)));
          const glm::dvec3 c = 1.2 * dir;
          const glm::dvec3 across = glm::normalize(glm::cross(dir, glm::dvec3(0.0, 1.0, 0.0)));
          const glm::dvec3 axis = glm::normalize(std::cos(turn) * across + std::sin(turn) * dir);
          const double radius = 0.15;
          const s::LtcFrame f = s::ltcFrame(glm::vec3(0, 0, 1), v, entry);
          const double expected = overCapsule(c, axis, hl, radius, [&](glm::dvec3 l) {
            const glm::vec3 w(glm::dot(glm::vec3(l), f.t1), glm::dot(glm::vec3(l), f.t2),
                              glm::dot(glm::vec3(l), f.n));
            return static_cast<double>(s::ltcDensity(entry, w));
          });
          const double got =
              s::ltcCapsuleIntegral(f, glm::vec3(c), glm::vec3(axis), static_cast<float>(hl),
                                    static_cast<float>(radius))
                  .z;
          const double error = std::abs(got - expected) / std::max(expected, 1e-3);
          worst = std::max(worst, error);
          EXPECT_LT(error, 0.01) << entry.x << " " << theta << " " << turn << " " << hl << ": "
                                 << got << " for " << expected;
        }
  std::printf("capsule polygon: worst relative error %.5f\n", worst);
}

// The second table, Heitz et al. 2016's norm and Fresnel term (their second texture), against the
// GGX lobe integrated here with Schlick's Fresnel, F0 (norm - fresnel) + fresnel the lobe's
// directional albedo: at table nodes (where the lookup reads one entry) from n.v = 1 to 0.1 and
// roughness 0.2 to 1; and the mean direction against the lobe's first moment. Measured: the norm
// within 0.3 %, the albedo with Fresnel (F0 = 0.04 and 1) within 0.3 %, the mean direction within
// 0.002. A Fresnel term weighted by (1 - n.l)^5 instead of (1 - v.h)^5 is 30 % off at F0 = 0.04.
TEST(Ltc, NormTableIsTheLobesAlbedoWithFresnel) {
  const ibl::LtcTable& table = ibl::ltcGgxTable();
  const int last = table.size - 1;
  double worstNorm = 0.0, worstAlbedo = 0.0, worstDirection = 0.0;
  for (int column : {last / 5, last / 2, last})
    for (int row : {0, last / 3, (2 * last) / 3, (9 * last) / 10}) {
      const double roughness = static_cast<double>(column) / last;
      const double alpha = std::max(roughness * roughness, 1e-3);
      const double NoV = ibl::ltcRowCosTheta(row, table.size);
      const glm::dvec3 v(std::sqrt(std::max(0.0, 1.0 - NoV * NoV)), 0.0, NoV);
      const double norm = ggxAlbedo(v, alpha);
      const double fresnel = overHemisphere([&](glm::dvec3 l) {
        const double vh = std::max(0.0, glm::dot(v, glm::normalize(v + l)));
        return ggxLobe(v, l, alpha) * std::pow(1.0 - vh, 5.0);
      });
      const double meanX = overHemisphere([&](glm::dvec3 l) { return ggxLobe(v, l, alpha) * l.x; });
      const double meanZ = overHemisphere([&](glm::dvec3 l) { return ggxLobe(v, l, alpha) * l.z; });
      const glm::vec4 got =
          ibl::ltcNormLookup(static_cast<float>(roughness), static_cast<float>(NoV));
      // The fitter's rule itself (what wrote the table), at the same place.
      const ibl::LtcNorm rule =
          ibl::ltcLobeAverages(static_cast<float>(alpha), static_cast<float>(NoV));
      for (double f0 : {0.04, 1.0}) {
        const double expected = f0 * (norm - fresnel) + fresnel;
        EXPECT_NEAR(f0 * (rule.norm - rule.fresnel) + rule.fresnel, expected, 0.01 * expected)
            << "the rule at " << roughness << " " << NoV << " " << f0;
      }
      worstNorm = std::max(worstNorm, std::abs(got.x - norm) / norm);
      for (double f0 : {0.04, 1.0}) {
        const double expected = f0 * (norm - fresnel) + fresnel;
        const double albedo = f0 * (got.x - got.y) + got.y;
        worstAlbedo = std::max(worstAlbedo, std::abs(albedo - expected) / expected);
        EXPECT_NEAR(albedo, expected, 0.01 * expected) << roughness << " " << NoV << " " << f0;
      }
      worstDirection = std::max(
          {worstDirection, std::abs(got.z - meanX / norm), std::abs(got.w - meanZ / norm)});
      EXPECT_NEAR(got.z, meanX / norm, 0.01) << roughness << " " << NoV;
      EXPECT_NEAR(got.w, meanZ / norm, 0.01) << roughness << " " << NoV;
    }
  std::printf("norm %.5f, albedo with Fresnel %.5f, mean direction %.5f\n", worstNorm, worstAlbedo,
              worstDirection);
  EXPECT_LT(worstNorm, 0.01);
}

// The shipped table is the fitter's output, across the table: entries from n.v = 1 to near
// grazing in three columns fitted again (at the n.v ltcRowCosTheta gives each row) and compared
// with the table. ibl_ltc_fit starts each row from the previous row's parameters; here every fit
// starts from (alpha, alpha, 0, 0) and still lands within 5e-4 of the shipped entry (measured
// 4.3e-4 at worst, row 22 of column 6), while fitting a row at another n.v moves its entries by
// 2 % to 34 % (rows at n.v = 1 - t instead of 1 - t^2: 2.2 % at row 28 of column 24). Row 0 alone
// would not do: every row-to-n.v mapping gives it n.v = 1. About 1.7 s in Release (12 fits).
TEST(Ltc, TableIsTheFittersOutput) {
  const ibl::LtcTable& table = ibl::ltcGgxTable();
  ASSERT_EQ(table.size, 64);
  for (int column : {12, 28, 48})
    for (int row : {0, 16, 32, 48}) {
      const float alpha = ibl::ltcColumnAlpha(column, table.size);
      // Row 0 (n.v = 1) is fitted isotropic, as the fitter does.
      const ibl::LtcFit fit = ibl::fitLtc(alpha, ibl::ltcRowCosTheta(row, table.size),
                                          glm::vec4(alpha, alpha, 0, 0), row == 0);
      const glm::vec4 shipped = table.entries[static_cast<std::size_t>(row) * table.size + column];
      for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(fit.entry[k], shipped[k], 2e-3f * std::max(1.0f, std::abs(shipped[k])))
            << "column " << column << " row " << row << " component " << k;
      if (row == 0) {
        EXPECT_LT(fit.error, 0.05f) << column;  // the L1 distance, measured <= 0.035
      }
    }
}

namespace {

// The L1 distance between the LTC `entry` and the GGX lobe of `alpha` seen at n.v (normalized
// by its integral), the integral of their difference's magnitude over the sphere: the midpoint
// rule in (x, phi) over each hemisphere with |cos theta| = 1 - x^2 (points crowded toward the
// normal), phi over the half circle y >= 0 doubled (both lobes are symmetric about the xz plane).
double ltcDistanceToGgx(glm::vec4 entry, double alpha, double NoV) {
  constexpr int n = 400;  // 1e-4 from the distance with 2000
  const glm::dvec3 v(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
  const auto overSphere = [&](const auto& f) {
    double sum = 0.0;
    for (double side : {1.0, -1.0})
      for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5) / n, c = 1.0 - x * x, sn = std::sqrt(1.0 - c * c);
        for (int j = 0; j < n; ++j) {
          const double phi = kPi * (j + 0.5) / n;
          sum += f(glm::dvec3(sn * std::cos(phi), sn * std::sin(phi), side * c)) * 2.0 * x;
        }
      }
    return 2.0 * sum * (1.0 / n) * (kPi / n);
  };
  const double albedo = overSphere([&](glm::dvec3 l) { return ggxLobe(v, l, alpha); });
  return overSphere([&](glm::dvec3 l) {
    return std::abs(ggxLobe(v, l, alpha) / albedo - s::ltcDensity(entry, glm::vec3(l)));
  });
}

}  // namespace

// Which n.v each row of the shipped table holds, checked apart from the fitter: the entry that
// ltcTableLookup returns at a row's n.v (sqrt(1 - n.v) = row / 31, where the lookup reads that
// row alone) against the GGX lobe written here at that n.v, by the L1 distance above, and against
// the lobe at the n.v a linear mapping (n.v = 1 - row / 31) would give the row, which must be
// farther. A table whose rows were fitted at another n.v than the lookup reads fails both.
// Measured: 0.008 to 0.144 down to n.v 0.54, 0.14 to 0.34 at n.v 0.24 (the fit's own error grows
// toward grazing); the linear mapping's lobe 0.11 to 1.6 away (1.2 to 20 times farther).
TEST(Ltc, TableRowsHoldTheLobeAtTheirNoV) {
  for (int column : {16, 32, 48})
    for (int row : {6, 18, 30, 42, 54}) {
      const double t = row / 63.0, roughness = column / 63.0, alpha = roughness * roughness;
      const double NoV = 1.0 - t * t;
      const glm::vec4 entry =
          ibl::ltcTableLookup(static_cast<float>(roughness), static_cast<float>(NoV));
      const double own = ltcDistanceToGgx(entry, alpha, NoV);
      const double linear = ltcDistanceToGgx(entry, alpha, 1.0 - t);
      std::printf("roughness %.3f, n.v %.3f: L1 %.4f to its lobe, %.4f to the lobe at n.v %.3f\n",
                  roughness, NoV, own, linear, 1.0 - t);
      EXPECT_LT(own, row < 54 ? 0.16 : 0.36) << column << " " << row;
      EXPECT_LT(own, linear) << column << " " << row;
    }
}
