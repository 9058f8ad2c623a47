// The table of linearly transformed cosines (ibl/render/ltc.hpp) against quadrature written here:
// the table's GGX lobe over rects and disks against the BRDF integrated over them, its norm and
// Fresnel table against the lobe's albedo, and the table against the fitter that wrote it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "ibl/render/ltc.hpp"
#include "ibl/shared/ltc.h"
#include "support/numbers.hpp"
#include "support/quadrature.hpp"

namespace s = ibl::shared;
using ibl::test::completeFrame;
using ibl::test::direction;
using ibl::test::Rect;
using ibl::test::rectToward;

namespace {

using ibl::test::kPi;

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

}  // namespace

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
