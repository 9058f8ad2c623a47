#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/bake/prefilter.hpp"
#include "ibl/math/color.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

CubeMap constantSource(int size, glm::vec3 value) {
  CubeMap cube = cubeFromFunction(size, [&](glm::vec3) { return value; });
  buildMipChain(cube);
  return cube;
}

// A dim sky with a small, very bright light (about 5 degrees across): what makes naive
// prefiltering noisy or blotchy.
CubeMap sunSource(int size) {
  const glm::vec3 sunDir = glm::normalize(glm::vec3(0.5f, 0.4f, -0.7f));
  CubeMap cube = cubeFromFunction(size, [&](glm::vec3 d) {
    const float sky = 0.2f + 0.3f * std::max(0.0f, d.y);
    return glm::vec3(sky) + (glm::dot(d, sunDir) > std::cos(0.045f)
                                 ? glm::vec3(3000.0f, 2500.0f, 2000.0f)
                                 : glm::vec3(0.0f));
  });
  buildMipChain(cube);
  return cube;
}

double relativeRmseLuminance(const std::array<Image, 6>& a, const std::array<Image, 6>& ref) {
  double num = 0.0, den = 0.0;
  for (int f = 0; f < 6; ++f)
    for (std::size_t i = 0; i < a[f].pixels.size(); ++i) {
      const double x = luminance(a[f].pixels[i]), y = luminance(ref[f].pixels[i]);
      num += (x - y) * (x - y);
      den += y * y;
    }
  return std::sqrt(num / den);
}

// The prefiltered radiance by brute force, written apart from the library: quadrature over
// every texel of a source level in double precision, texel solid angles by a 4 x 4 midpoint
// rule on the face plane, and the lobes from their papers with n = v:
//   standard  D(h) (n.l)                     D: Walter et al. 2007, eq. 33
//   F0 = 1    D(h) V(l) (n.l)                V = G2 / (4 (n.v)(n.l)), G2 = 1 / (1 + Lambda(l)),
//                                            Lambda = (sqrt(1 + a^2 tan^2) - 1) / 2 (Heitz 2014)
//   F0 = 0    D(h) V(l) (1 - v.h)^5 (n.l)    Schlick 1994
class IndependentSource {
 public:
  explicit IndependentSource(const std::array<Image, 6>& level) {
    const int n = level[0].width;
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          double omega = 0.0;
          for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
              const double s = 2.0 * (x + (i + 0.5) / 4) / n - 1.0;
              const double t = 2.0 * (y + (j + 0.5) / 4) / n - 1.0;
              omega += 4.0 / (16.0 * n * n) / std::pow(1.0 + s * s + t * t, 1.5);
            }
          texels_.push_back(
              {glm::dvec3(texelDirection(f, x, y, n)), glm::dvec3(level[f].at(x, y)), omega});
        }
  }

  glm::dvec3 prefiltered(glm::dvec3 n, double roughness, PrefilterWeight weight) const {
    const double a = roughness * roughness, a2 = a * a;
    glm::dvec3 sum(0.0);
    double wsum = 0.0;
    for (const auto& t : texels_) {
      const double nl = glm::dot(n, t.dir);
      if (nl <= 0.0) continue;
      const glm::dvec3 h = glm::normalize(n + t.dir);
      const double nh = glm::dot(n, h);
      const double q = nh * nh * (a2 - 1.0) + 1.0;
      const double d = a2 / (std::numbers::pi * q * q);
      double w = d * nl;
      if (weight != PrefilterWeight::Standard) {
        const double tan2 = (1.0 - nl * nl) / (nl * nl);
        const double lambda = (std::sqrt(1.0 + a2 * tan2) - 1.0) / 2.0;
        w *= 1.0 / (1.0 + lambda) / (4.0 * nl);
        const double m = 1.0 - nh;  // v.h = n.h
        if (weight == PrefilterWeight::FresnelF0Zero) w *= m * m * m * m * m;
      }
      sum += w * t.omega * t.radiance;
      wsum += w * t.omega;
    }
    return sum / wsum;
  }

  // Relative RMSE of luminance of a level against the reference at its texels (every
  // `stride`-th in x and y).
  double relativeRmse(const std::array<Image, 6>& level, double roughness, PrefilterWeight weight,
                      int stride = 1) const {
    const int n = level[0].width;
    double num = 0.0, den = 0.0;
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; y += stride)
        for (int x = 0; x < n; x += stride) {
          const glm::dvec3 ref =
              prefiltered(glm::dvec3(texelDirection(f, x, y, n)), roughness, weight);
          const double e = luminance(level[f].at(x, y)) - luminance(glm::vec3(ref));
          num += e * e;
          den += std::pow(luminance(glm::vec3(ref)), 2.0);
        }
    return std::sqrt(num / den);
  }

 private:
  struct Texel {
    glm::dvec3 dir, radiance;
    double omega;
  };
  std::vector<Texel> texels_;
};

}  // namespace

TEST(Prefilter, RoughnessMappings) {
  EXPECT_FLOAT_EQ(roughnessForLevel(0, 6, RoughnessMapping::Linear), 0.0f);
  EXPECT_FLOAT_EQ(roughnessForLevel(2, 6, RoughnessMapping::Linear), 0.4f);
  EXPECT_FLOAT_EQ(roughnessForLevel(5, 6, RoughnessMapping::Linear), 1.0f);
  EXPECT_FLOAT_EQ(roughnessForLevel(2, 6, RoughnessMapping::Frostbite), 0.16f);
  EXPECT_EQ(defaultSpecularLevels(256), 6);  // 256 .. 8
  EXPECT_EQ(defaultSpecularLevels(8), 1);
}

TEST(Prefilter, ConstantEnvironmentStaysConstant) {
  const glm::vec3 L(1.5f, 0.75f, 3.0f);
  const CubeMap source = constantSource(64, L);
  for (auto method : {PrefilterMethod::Direct, PrefilterMethod::Sampled})
    for (auto weight : {PrefilterWeight::Standard, PrefilterWeight::FresnelF0Zero,
                        PrefilterWeight::FresnelF0One}) {
      PrefilterOptions o;
      o.size = 64;
      o.levels = 4;
      o.method = method;
      o.weight = weight;
      o.samples = 32;
      const CubeMap out = prefilterGgx(source, o);
      ASSERT_EQ(out.levelCount(), 4);
      for (int m = 0; m < 4; ++m)
        for (const auto& face : out.levels[m])
          for (const auto& p : face.pixels) {
            ASSERT_NEAR(p.x, L.x, 3e-5f * L.x) << "level " << m;
            ASSERT_NEAR(p.z, L.z, 3e-5f * L.z) << "level " << m;
          }
    }
  const CubeMap irradiance = convolveIrradiance(source, 16, levelOfSize(source, 16));
  for (const auto& face : irradiance.levels[0])
    for (const auto& p : face.pixels) ASSERT_NEAR(p.y, L.y, 3e-5f);
}

TEST(Prefilter, LevelZeroIsTheSource) {
  const CubeMap source = sunSource(32);
  PrefilterOptions o;
  o.size = 32;
  const CubeMap out = prefilterGgx(source, o);
  for (int f = 0; f < 6; ++f) EXPECT_EQ(out.levels[0][f].pixels, source.levels[0][f].pixels);
}

TEST(Prefilter, CoarseLevelsComputedSmallerAndInterpolated) {
  // Three levels of 128^2: r = 0.5 at 64^2 has 10 texels per lobe half width (kept: half as
  // many would be too few), r = 1 at 32^2 has 22, more than it needs: it is computed at 16^2
  // and interpolated up, and must still match quadrature over every texel of the source.
  const CubeMap source = sunSource(128);
  const IndependentSource ref(source.levels[0]);
  PrefilterOptions o;
  o.size = 128;
  o.levels = 3;
  std::vector<LevelMethod> methods;
  const CubeMap out = prefilterGgx(source, o, &methods);
  EXPECT_EQ(methods[1].computedSize, 64);
  EXPECT_EQ(methods[2].computedSize, 16);
  for (int m = 1; m < 3; ++m) {
    const double e =
        ref.relativeRmse(out.levels[m], methods[m].roughness, PrefilterWeight::Standard, 3);
    RecordProperty("level " + std::to_string(m), std::to_string(e));
    EXPECT_LT(e, 3e-3) << "level " << m;
  }
}

TEST(Prefilter, LevelsAgainstAnIndependentReference) {
  // Every level and every weight against independentPrefilter (its own GGX, Smith and Fresnel
  // terms and solid angles, quadrature over all 24576 texels of the 64^2 source).
  const CubeMap source = sunSource(64);
  const IndependentSource ref(source.levels[0]);
  const std::pair<PrefilterWeight, const char*> weights[] = {
      {PrefilterWeight::Standard, "standard"},
      {PrefilterWeight::FresnelF0One, "F0 = 1"},
      {PrefilterWeight::FresnelF0Zero, "F0 = 0"}};
  for (const auto& [weight, name] : weights) {
    PrefilterOptions o;
    o.size = 64;
    o.levels = 4;  // roughness 0, 1/3, 2/3, 1
    o.weight = weight;
    std::vector<LevelMethod> methods;
    const CubeMap out = prefilterGgx(source, o, &methods);
    for (int m = 1; m < 4; ++m) {
      const double e =
          ref.relativeRmse(out.levels[m], methods[m].roughness, weight, m == 1 ? 3 : 1);
      RecordProperty(std::string(name) + " level " + std::to_string(m), std::to_string(e));
      EXPECT_LT(e, 3e-3) << name << ", level " << m << " (" << methods[m].method << ")";
    }
    // Filtered importance sampling is smooth but biased: the fallback, not the default. (For
    // F0 = 0 it is far off: its samples follow D, the lobe's weight lies where D is small.)
    if (weight == PrefilterWeight::FresnelF0Zero) continue;
    o.method = PrefilterMethod::Sampled;
    o.samples = 64;
    const CubeMap sampled = prefilterGgx(source, o, &methods);
    const double e = ref.relativeRmse(sampled.levels[1], methods[1].roughness, weight, 3);
    EXPECT_GT(e, 0.01) << name;
    EXPECT_LT(e, 0.15) << name;
  }
}

TEST(Prefilter, RingsMatchDirectQuadratureForSharpLobes) {
  const CubeMap source = sunSource(128);
  LevelMethod method;
  const auto rings = prefilterLevelRings(source, 64, 0.2f, PrefilterWeight::Standard, &method);
  EXPECT_EQ(method.method, "rings");
  const auto ref = prefilterLevelDirect(source, 0, 64, 0.2f, PrefilterWeight::Standard);
  EXPECT_LT(relativeRmseLuminance(rings, ref), 0.01);
}

TEST(Prefilter, IrradianceOfASkyMatchesTheClosedForm) {
  // Upper hemisphere of radiance 1: E(n) / pi = (1 + n.y) / 2.
  CubeMap sky = cubeFromFunction(64, [](glm::vec3 d) { return glm::vec3(d.y > 0 ? 1.0f : 0.0f); });
  buildMipChain(sky);
  const CubeMap irr = convolveIrradiance(sky, 16, levelOfSize(sky, 32));
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        const glm::vec3 n = texelDirection(f, x, y, 16);
        ASSERT_NEAR(irr.levels[0][f].at(x, y).x, 0.5f * (1.0f + n.y), 5e-3f);
      }
}
