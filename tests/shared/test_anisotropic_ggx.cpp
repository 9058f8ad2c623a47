// KHR_materials_anisotropy's GGX (ibl/shared/brdf.h, sampling.h, material.h, path_brdf.h)
// against computations written here: the distribution's projected area and the visible normals'
// normalization by a midpoint rule over the hemisphere, the visible-normal samples' moments
// against that rule, the extension's own form of D, the direction's rotation and the spec's
// alpha rule at chosen values, and the reference's lobe: its samples weigh what its evaluation
// integrates to, and the microfacet walk keeps a white lobe's energy.
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/shared/material.h"
#include "ibl/shared/path_brdf.h"
#include "ibl/shared/sampling.h"
#include "ibl/shared/split_sum.h"

using namespace ibl;

namespace {

constexpr double kAnisotropyPi = std::numbers::pi;

// The midpoint rule over the upper hemisphere in (theta, phi), finer near the pole where the
// lobes peak: theta = (pi / 2) u^2.
double anisotropicHemisphereIntegral(const std::function<double(glm::dvec3)>& f,
                                     int thetaSteps = 1500, int phiSteps = 360) {
  double sum = 0.0;
  for (int i = 0; i < thetaSteps; ++i) {
    const double u = (i + 0.5) / thetaSteps;
    const double theta = 0.5 * kAnisotropyPi * u * u, dTheta = kAnisotropyPi * u / thetaSteps;
    for (int j = 0; j < phiSteps; ++j) {
      const double phi = 2.0 * kAnisotropyPi * (j + 0.5) / phiSteps;
      const glm::dvec3 w(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                         std::cos(theta));
      sum += f(w) * std::sin(theta) * dTheta * (2.0 * kAnisotropyPi / phiSteps);
    }
  }
  return sum;
}

// Anisotropic GGX written from Heitz 2014 (eq. 85, and Lambda of eq. 86 with the roughness
// projected on the azimuth), in doubles.
double heitzD(glm::dvec3 h, double ax, double ay) {
  if (h.z <= 0.0) return 0.0;
  const double c2 = h.z * h.z, tan2 = (1.0 - c2) / c2;
  const double phiTerm =
      tan2 > 0.0 ? (h.x * h.x / (ax * ax) + h.y * h.y / (ay * ay)) / (h.x * h.x + h.y * h.y) : 0.0;
  const double k = 1.0 + tan2 * phiTerm;
  return 1.0 / (kAnisotropyPi * ax * ay * c2 * c2 * k * k);
}
double heitzLambda(glm::dvec3 w, double ax, double ay) {
  const double s2 = w.x * w.x + w.y * w.y;
  if (s2 <= 0.0) return 0.0;
  const double alpha2 = (w.x * w.x * ax * ax + w.y * w.y * ay * ay) / s2;
  const double tan2 = s2 / (w.z * w.z);
  return 0.5 * (-1.0 + std::sqrt(1.0 + alpha2 * tan2));
}

struct LobeAlphas {
  float x, y;
};
const LobeAlphas kLobeAlphas[] = {{0.6f, 0.1f}, {0.15f, 0.45f}, {0.3f, 0.3f}, {1.0f, 0.25f}};

}  // namespace

// The microfacets' projected area is the surface's: integral of D(h) (n.h) = 1 (Heitz 2014,
// eq. 4), for lobes stretched along x, along y, and round.
TEST(AnisotropicGgx, DistributionProjectsToTheSurface) {
  for (const LobeAlphas a : kLobeAlphas) {
    const double area = anisotropicHemisphereIntegral([&](glm::dvec3 h) {
      return shared::ggxDistributionAnisotropic(glm::vec3(h), glm::vec2(a.x, a.y)) * h.z;
    });
    EXPECT_NEAR(area, 1.0, 2e-3) << a.x << " " << a.y;
  }
}

// D equals the form the extension's text gives (a2 = at ab, f = (ab t.h, at b.h, a2 n.h),
// D = a2 (a2 / f.f)^2 / pi) and Heitz's, and with ax = ay the isotropic D.
TEST(AnisotropicGgx, DistributionIsTheExtensionsAndHeitzs) {
  for (const LobeAlphas a : kLobeAlphas)
    for (glm::dvec3 h : {glm::dvec3(0.3, -0.2, 0.9), glm::dvec3(-0.7, 0.1, 0.4),
                         glm::dvec3(0.05, 0.6, 0.5), glm::dvec3(0.0, 0.0, 1.0)}) {
      h = glm::normalize(h);
      const double a2 = double(a.x) * a.y;
      const glm::dvec3 f(a.y * h.x, a.x * h.y, a2 * h.z);
      const double w2 = a2 / glm::dot(f, f);
      const double extension = a2 * w2 * w2 / kAnisotropyPi;
      const double d = shared::ggxDistributionAnisotropic(glm::vec3(h), glm::vec2(a.x, a.y));
      EXPECT_NEAR(d, extension, 1e-4 * extension);
      EXPECT_NEAR(d, heitzD(h, a.x, a.y), 1e-4 * extension);
      if (a.x == a.y) {
        EXPECT_NEAR(d, shared::ggxDistribution(static_cast<float>(h.z), a.x), 1e-4 * d);
      }
    }
}

// The visible normals' density integrates to one: integral of G1(v) max(0, v.h) D(h) = n.v
// (Heitz 2014, eq. 14), for views along and across the stretch; and G1 = 1 / (1 + Lambda) with
// Lambda written here.
TEST(AnisotropicGgx, VisibleNormalsIntegrateToTheView) {
  for (const LobeAlphas a : kLobeAlphas)
    for (float phi : {0.0f, 0.9f, 1.5708f})
      for (float cosTheta : {0.9f, 0.5f, 0.2f}) {
        const float s = std::sqrt(1.0f - cosTheta * cosTheta);
        const glm::vec3 v(s * std::cos(phi), s * std::sin(phi), cosTheta);
        const float g1 = shared::smithGgxMaskingAnisotropic(v, glm::vec2(a.x, a.y));
        EXPECT_NEAR(g1, 1.0 / (1.0 + heitzLambda(glm::dvec3(v), a.x, a.y)), 1e-5);
        const double projected = anisotropicHemisphereIntegral([&](glm::dvec3 h) {
          return g1 * std::max(0.0, glm::dot(glm::dvec3(v), h)) * heitzD(h, a.x, a.y);
        });
        EXPECT_NEAR(projected, cosTheta, 3e-3) << a.x << " " << a.y << " phi " << phi;
      }
}

// The visible-normal samples (Heitz 2018, anisotropic) are distributed with G1 max(0, v.h) D / n.v:
// their moments h.x^2, h.y^2 and h.x h.y over 2^16 points equal the density's, by the midpoint
// rule. An unstretch with the alphas swapped, or no stretch at all, moves them by far more.
TEST(AnisotropicGgx, VisibleNormalSamplesFollowTheirDensity) {
  const glm::vec3 v = glm::normalize(glm::vec3(0.5f, 0.3f, 0.6f));
  for (const LobeAlphas a : {kLobeAlphas[0], kLobeAlphas[1]}) {
    const std::uint32_t n = 1u << 16;
    glm::dvec3 sampled(0.0);
    for (std::uint32_t i = 0; i < n; ++i) {
      const glm::vec3 h = shared::sampleGgxVisibleNormalAnisotropic(v, shared::hammersley(i, n),
                                                                    glm::vec2(a.x, a.y));
      sampled += glm::dvec3(h.x * h.x, h.y * h.y, h.x * h.y) / double(n);
    }
    const double g1 = 1.0 / (1.0 + heitzLambda(glm::dvec3(v), a.x, a.y));
    const auto moment = [&](const std::function<double(glm::dvec3)>& g) {
      return anisotropicHemisphereIntegral([&](glm::dvec3 h) {
        return g(h) * g1 * std::max(0.0, glm::dot(glm::dvec3(v), h)) * heitzD(h, a.x, a.y) / v.z;
      });
    };
    EXPECT_NEAR(sampled.x, moment([](glm::dvec3 h) { return h.x * h.x; }), 2e-3) << a.x;
    EXPECT_NEAR(sampled.y, moment([](glm::dvec3 h) { return h.y * h.y; }), 2e-3) << a.x;
    EXPECT_NEAR(sampled.z, moment([](glm::dvec3 h) { return h.x * h.y; }), 2e-3) << a.x;
  }
}

// The extension's direction and roughness: the default direction (1, 0) turned counterclockwise
// by the rotation; a texture's RG from [0, 1] to [-1, 1], normalized, then turned (the Khronos
// AnisotropyRotationTest: a texture at -30 degrees and a rotation of +30 lie along the tangent);
// B scales the strength; alpha_t = mix(r^2, 1, s^2), alpha_b = r^2.
TEST(AnisotropicGgx, DirectionAndRoughnessFollowTheExtension) {
  const glm::vec4 none(1.0f, 0.5f, 1.0f, 1.0f);
  const float degree = static_cast<float>(kAnisotropyPi / 180.0);
  glm::vec3 d = shared::anisotropyDirectionOf(30.0f * degree, none);
  EXPECT_NEAR(d.x, std::sqrt(3.0f) / 2.0f, 1e-6f);
  EXPECT_NEAR(d.y, 0.5f, 1e-6f);
  EXPECT_EQ(d.z, 1.0f);
  d = shared::anisotropyDirectionOf(90.0f * degree, none);
  EXPECT_NEAR(d.x, 0.0f, 1e-6f);
  EXPECT_NEAR(d.y, 1.0f, 1e-6f);
  // RG at -30 degrees (scaled by 0.6: the texture need not hold unit vectors), B 0.25.
  const glm::vec4 texel(0.5f + 0.3f * std::cos(30.0f * degree),
                        0.5f - 0.3f * std::sin(30.0f * degree), 0.25f, 1.0f);
  d = shared::anisotropyDirectionOf(30.0f * degree, texel);
  EXPECT_NEAR(d.x, 1.0f, 1e-5f);
  EXPECT_NEAR(d.y, 0.0f, 1e-5f);
  EXPECT_EQ(d.z, 0.25f);
  const glm::vec2 alpha = shared::anisotropicAlpha(0.4f, 0.5f);
  EXPECT_NEAR(alpha.x, 0.16f * 0.75f + 0.25f, 1e-6f);
  EXPECT_NEAR(alpha.y, 0.16f, 1e-6f);
}

// The direction in world space: x along the tangent made orthogonal to the normal, y along the
// bitangent w (n x t); the built-in spheres' tangent runs along the parallels (parallel to the
// derivative of the position in longitude about +Y; its sign is immaterial, the lobe being
// symmetric under t -> -t, and with it b -> -b).
TEST(AnisotropicGgx, TangentFrameIsGltfs) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  const glm::vec3 along =
      shared::anisotropyTangentOf(n, glm::vec4(2.0f, 0.0f, 1.0f, 1.0f), glm::vec2(1.0f, 0.0f));
  EXPECT_LT(glm::distance(along, glm::vec3(1.0f, 0.0f, 0.0f)), 1e-6f);
  const glm::vec3 up =
      shared::anisotropyTangentOf(n, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f), glm::vec2(0.0f, 1.0f));
  EXPECT_LT(glm::distance(up, glm::vec3(0.0f, 1.0f, 0.0f)), 1e-6f);
  const glm::vec3 down =
      shared::anisotropyTangentOf(n, glm::vec4(1.0f, 0.0f, 0.0f, -1.0f), glm::vec2(0.0f, 1.0f));
  EXPECT_LT(glm::distance(down, glm::vec3(0.0f, -1.0f, 0.0f)), 1e-6f);
  for (float longitude : {0.3f, 2.0f, -1.2f}) {
    const float latitude = 0.4f;
    const auto position = [&](float phi) {
      return glm::vec3(std::cos(latitude) * std::cos(phi), std::sin(latitude),
                       -std::cos(latitude) * std::sin(phi));
    };
    const glm::vec3 parallel =
        glm::normalize(position(longitude + 1e-3f) - position(longitude - 1e-3f));
    const glm::vec4 t = shared::sphereTangent(position(longitude));
    EXPECT_GT(std::abs(glm::dot(glm::vec3(t), parallel)), 0.9999f) << longitude;
    EXPECT_EQ(t.w, 1.0f);
  }
}

// The split sum's bent normal: at full strength on a mirror the normal bends all the way to the
// view's part across the stretch, so a view in the (t, n) plane reads the map along itself; at
// strength 0 the map is read along the mirror reflection.
TEST(AnisotropicGgx, SplitSumReadsAlongTheBentReflection) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f), t(1.0f, 0.0f, 0.0f);
  const glm::vec3 v = glm::normalize(glm::vec3(0.6f, 0.0f, 0.8f));
  shared::SplitSumSwitches s{};
  shared::SplitSumMaterial m{};
  m.roughness = 0.0f;
  m.anisotropy = 1.0f;
  m.anisotropyTangent = t;
  const shared::SplitSumLookup look =
      shared::anisotropicLookup(shared::splitSumLookup(n, v, 0.0f, s), n, v, m, s);
  EXPECT_LT(glm::distance(look.specularDirection, v), 1e-5f);
  m.anisotropy = 0.0f;
  const shared::SplitSumLookup mirror =
      shared::anisotropicLookup(shared::splitSumLookup(n, v, 0.0f, s), n, v, m, s);
  EXPECT_LT(glm::distance(mirror.specularDirection, glm::vec3(-0.6f, 0.0f, 0.8f)), 1e-5f);
  // Partly bent, a view off the (t, n) plane: strength 0.6 at roughness 0.3 bends by
  // 1 - (1 - 0.6 x 0.7)^4 = 1 - 0.58^4 from n toward the view without its b part, (0.3, 0,
  // 0.866) here; the map is read along the view reflected about that normal.
  const glm::vec3 w = glm::normalize(glm::vec3(0.3f, 0.4f, 0.866f));
  m.anisotropy = 0.6f;
  m.roughness = 0.3f;
  const float keep = std::pow(0.58f, 4.0f);
  const glm::vec3 bent = glm::normalize((1.0f - keep) * glm::vec3(w.x, 0.0f, w.z) + keep * n);
  const glm::vec3 expected = 2.0f * glm::dot(bent, w) * bent - w;
  const shared::SplitSumLookup partly =
      shared::anisotropicLookup(shared::splitSumLookup(n, w, 0.3f, s), n, w, m, s);
  EXPECT_LT(glm::distance(partly.specularDirection, expected), 1e-5f);
}

namespace {

const std::vector<float> kAnisotropyNoTables(static_cast<std::size_t>(shared::kAlbedoTableNodes) *
                                                 shared::kAlbedoTableNodes,
                                             0.0f);

// A white metal (F0 = F90 = 1) with anisotropy along local `tangent`, seen from v.
shared::PathBrdf whiteAnisotropicMetal(glm::vec3 v, float roughness, float strength,
                                       glm::vec3 tangent, int multipleScattering) {
  const shared::AlbedoTables tables{kAnisotropyNoTables.data(), kAnisotropyNoTables.data()};
  shared::PathShading o{};
  o.diffuseModel = 1;
  o.multipleScattering = multipleScattering;
  shared::SpecularReflectance white = shared::schlickReflectance(glm::vec3(1.0f), 1.0f);
  shared::PathBrdf b = shared::pathBrdfOf(tables, glm::vec3(1.0f), 1.0f, roughness, white,
                                          glm::vec3(0.0f), 0.0f, v, shared::kLobesAll, o);
  return shared::withAnisotropy(tables, b, strength, tangent, v, o);
}

}  // namespace

// The reference's anisotropic lobe: the mean weight of its samples is the integral of its
// evaluation f cos over the hemisphere (the midpoint rule), which is also the single-scattering
// albedo written here from Heitz's D and Lambda; with the microfacet walk, a white lobe reflects
// everything (no energy lost between its microfacets, Heitz et al. 2016).
TEST(AnisotropicGgx, ReferenceLobeSamplesWeighWhatItReflects) {
  const shared::AlbedoTables tables{kAnisotropyNoTables.data(), kAnisotropyNoTables.data()};
  const glm::vec3 tangent = glm::normalize(glm::vec3(0.8f, 0.6f, 0.0f));
  for (float viewAzimuth : {0.0f, 1.2f}) {
    const glm::vec3 v(0.6f * std::cos(viewAzimuth), 0.6f * std::sin(viewAzimuth), 0.8f);
    const shared::PathBrdf b =
        whiteAnisotropicMetal(v, 0.3f, 0.8f, tangent, shared::kMultipleScatteringOff);
    const glm::vec2 alpha = shared::anisotropicAlpha(0.3f, 0.8f);
    // The lobe's frame: x along the tangent.
    const glm::dvec3 t(tangent), bt = glm::cross(glm::dvec3(0.0, 0.0, 1.0), t);
    const auto lobe = [&](glm::dvec3 w) {
      return glm::dvec3(glm::dot(w, t), glm::dot(w, bt), w.z);
    };
    const glm::dvec3 vd(v);
    const double albedo = anisotropicHemisphereIntegral([&](glm::dvec3 l) {
      const glm::dvec3 h = glm::normalize(vd + l);
      const double g2 = 1.0 / (1.0 + heitzLambda(lobe(vd), alpha.x, alpha.y) +
                               heitzLambda(lobe(l), alpha.x, alpha.y));
      return heitzD(lobe(h), alpha.x, alpha.y) * g2 / (4.0 * vd.z);
    });
    const double evaluated = anisotropicHemisphereIntegral([&](glm::dvec3 l) {
      const shared::PathSampler unused = shared::pathSamplerAt(1u, 0u);
      return double(shared::evaluatePathBrdf(tables, b, v, glm::vec3(l), unused, true).x);
    });
    EXPECT_NEAR(evaluated, albedo, 2e-3 * albedo) << viewAzimuth;
    const std::uint32_t key = shared::pathSamplerKey(3u, 0u, 2u, 0u);
    const int n = 1 << 14;
    double mean = 0.0;
    for (int i = 0; i < n; ++i) {
      shared::PathSampler numbers = shared::pathSamplerAt(key, static_cast<std::uint32_t>(i));
      mean += shared::samplePathBrdf(tables, b, v, numbers).weight.x / double(n);
    }
    EXPECT_NEAR(mean, albedo, 5e-3) << viewAzimuth;
    // The samples' directions follow the density the lobe reports (pathBrdfPdf): their moments
    // l.x, l.y and l.x l.y against the density's, by the midpoint rule. Turning the sampled
    // normals back into the local frame the wrong way mirrors them about the tangent.
    glm::dvec3 sampledMoments(0.0);
    for (int i = 0; i < n; ++i) {
      shared::PathSampler numbers = shared::pathSamplerAt(key, static_cast<std::uint32_t>(i));
      const glm::dvec3 l(shared::samplePathBrdf(tables, b, v, numbers).direction);
      if (l.z > 0.0) sampledMoments += glm::dvec3(l.x, l.y, l.x * l.y) / double(n);
    }
    for (int k = 0; k < 3; ++k) {
      const double expected = anisotropicHemisphereIntegral([&](glm::dvec3 l) {
        const double moment = k == 0 ? l.x : (k == 1 ? l.y : l.x * l.y);
        return moment * shared::pathBrdfPdf(b, v, glm::vec3(l));
      });
      EXPECT_NEAR(sampledMoments[k], expected, 5e-3) << viewAzimuth << ", moment " << k;
    }
    // The walk's first order (its phase function and masking at the hit's height, which read
    // Lambda) has the expectation of the analytic lobe at points (Heitz et al. 2016, section 5).
    shared::Microsurface surface;
    surface.alpha = alpha;
    surface.reflectance = shared::schlickReflectance(glm::vec3(1.0f), 1.0f);
    for (const glm::vec3 l : {glm::normalize(glm::vec3(-0.5f, 0.3f, 0.7f)),
                              glm::normalize(glm::vec3(0.2f, -0.6f, 0.5f))}) {
      const glm::vec3 vl = glm::vec3(lobe(vd)), ll = glm::vec3(lobe(glm::dvec3(l)));
      double walked = 0.0;
      const int walks = 1 << 17;
      for (int i = 0; i < walks; ++i) {
        shared::PathSampler numbers =
            shared::pathSamplerAt(key + 1u, static_cast<std::uint32_t>(i));
        walked += shared::evaluateMicrofacetWalk(surface, vl, ll, numbers, 1, 1).x / double(walks);
      }
      const glm::dvec3 h = glm::normalize(lobe(vd) + lobe(glm::dvec3(l)));
      const double g2 = 1.0 / (1.0 + heitzLambda(lobe(vd), alpha.x, alpha.y) +
                               heitzLambda(lobe(glm::dvec3(l)), alpha.x, alpha.y));
      const double expected = heitzD(h, alpha.x, alpha.y) * g2 / (4.0 * vd.z);
      EXPECT_NEAR(walked, expected, 0.03 * expected) << viewAzimuth;
    }
    // The walk: every bounce reflects all of it.
    const shared::PathBrdf walk =
        whiteAnisotropicMetal(v, 0.3f, 0.8f, tangent, shared::kMultipleScatteringWalk);
    double walked = 0.0;
    for (int i = 0; i < n; ++i) {
      shared::PathSampler numbers = shared::pathSamplerAt(key, static_cast<std::uint32_t>(i));
      walked += shared::samplePathBrdf(tables, walk, v, numbers).weight.x / double(n);
    }
    EXPECT_NEAR(walked, 1.0, 5e-3) << viewAzimuth << ": single scattering " << albedo;
  }
}

// The isotropic tables are read for an anisotropic lobe at anisotropicTableRoughness: the
// isotropic lobe there reflects (single scattering, F = 1) within 0.07 of what the anisotropic
// lobe does, for views along and across the stretch at n.v 0.9 and 0.5, both albedos by the
// midpoint rule from Heitz's D and Lambda. The geometric mean of the alphas (0.25 for the first
// lobe, whose albedo is 0.55) is off by 0.4.
TEST(AnisotropicGgx, TableRoughnessHasTheLobesAlbedo) {
  const auto albedo = [](glm::dvec3 v, double ax, double ay) {
    return anisotropicHemisphereIntegral(
        [&](glm::dvec3 l) {
          const glm::dvec3 h = glm::normalize(v + l);
          const double g2 = 1.0 / (1.0 + heitzLambda(v, ax, ay) + heitzLambda(l, ax, ay));
          return heitzD(h, ax, ay) * g2 / (4.0 * v.z);
        },
        600, 240);
  };
  for (const glm::vec2 alpha :
       {shared::anisotropicAlpha(0.25f, 1.0f), shared::anisotropicAlpha(0.25f, 0.5f),
        shared::anisotropicAlpha(0.5f, 0.5f)}) {
    const double r = shared::anisotropicTableRoughness(alpha), a = r * r;
    for (double c : {0.9, 0.5})
      for (double phi : {0.0, 0.5 * kAnisotropyPi}) {
        const double s = std::sqrt(1.0 - c * c);
        const double anisotropic =
            albedo(glm::dvec3(s * std::cos(phi), s * std::sin(phi), c), alpha.x, alpha.y);
        EXPECT_NEAR(albedo(glm::dvec3(s, 0.0, c), a, a), anisotropic, 0.07)
            << alpha.x << " " << alpha.y << ", n.v " << c << ", azimuth " << phi;
      }
  }
}

// The reference's lobe turns with its direction: the material along tangent R t, seen from R v,
// is the material along t seen from v turned by R (a rotation about the normal), with the walk
// too (its bounces run in the lobe's frame): the same numbers give R times each sampled
// direction and each walk's estimate of f cos at R l. A walk run in the local frame, or its
// direction not turned back, breaks this (the lobe is far from round: strength 0.8).
TEST(AnisotropicGgx, ReferenceLobeTurnsWithItsDirection) {
  const shared::AlbedoTables tables{kAnisotropyNoTables.data(), kAnisotropyNoTables.data()};
  const float turn = 1.1f;
  const glm::mat3 r(glm::vec3(std::cos(turn), std::sin(turn), 0.0f),
                    glm::vec3(-std::sin(turn), std::cos(turn), 0.0f), glm::vec3(0.0f, 0.0f, 1.0f));
  const glm::vec3 t(1.0f, 0.0f, 0.0f);
  const glm::vec3 v = glm::normalize(glm::vec3(0.4f, 0.3f, 0.8f));
  const glm::vec3 l = glm::normalize(glm::vec3(-0.5f, 0.1f, 0.6f));
  const shared::PathBrdf b =
      whiteAnisotropicMetal(v, 0.3f, 0.8f, t, shared::kMultipleScatteringWalk);
  const shared::PathBrdf turned =
      whiteAnisotropicMetal(r * v, 0.3f, 0.8f, r * t, shared::kMultipleScatteringWalk);
  const std::uint32_t key = shared::pathSamplerKey(7u, 0u, 2u, 0u);
  int sameDirection = 0, sameValue = 0;
  const int n = 256;
  for (int i = 0; i < n; ++i) {
    shared::PathSampler numbers = shared::pathSamplerAt(key, static_cast<std::uint32_t>(i));
    shared::PathSampler again = numbers;
    const glm::vec3 d = shared::samplePathBrdf(tables, b, v, numbers).direction;
    const glm::vec3 dt = shared::samplePathBrdf(tables, turned, r * v, again).direction;
    if (glm::distance(r * d, dt) < 1e-3f) ++sameDirection;
    const shared::PathSampler walk = shared::pathSamplerAt(key + 1u, static_cast<std::uint32_t>(i));
    const float f = shared::evaluatePathBrdf(tables, b, v, l, walk, true).x;
    const float ft = shared::evaluatePathBrdf(tables, turned, r * v, r * l, walk, true).x;
    if (std::abs(f - ft) <= 1e-3f * std::max(f, 1e-3f)) ++sameValue;
  }
  // Rounding may send a rare walk another way.
  EXPECT_GE(sameDirection, n * 98 / 100);
  EXPECT_GE(sameValue, n * 98 / 100);
}
