#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/bake/dfg.hpp"
#include "ibl/core/stats.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/renderer.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

struct Baked {
  BakeOptions options;
  BakeResult result;
};

Baked bakeOf(const RadianceFn& f, int size = 64) {
  Baked b;
  b.options.specular.size = size;
  b.options.irradianceSize = 16;
  b.options.dfgSize = 64;
  b.options.dfgSamples = 1024;
  b.result = bakeEnvironment(equirectEnvironment(equirectFromFunction(512, f)), b.options);
  return b;
}

// An orthographic view of the unit sphere from +Z: pixel (n/2, n/2) looks at its center.
Camera sphereCamera(int n) {
  Camera c;
  c.perspective = false;
  c.orthoWidth = 2.0f;
  c.from = glm::vec3(0, 0, 5);
  c.width = c.height = n;
  return c;
}

Scene sphere(glm::vec3 base, float metallic, float roughness) {
  Material m;
  m.baseColor = base;
  m.metallic = metallic;
  m.roughness = roughness;
  return makeSphereScene(m);
}

// Pixels fully on the model in both renders (silhouette pixels mix in the background).
std::vector<float> interiorMask(const RenderResult& a, const RenderResult& b) {
  std::vector<float> m(a.alpha.size());
  for (std::size_t i = 0; i < m.size(); ++i)
    m[i] = a.alpha[i] == 1.0f && b.alpha[i] == 1.0f ? 1.0f : 0.0f;
  return m;
}

// The split sum (1 sample at each pixel center) against the reference (1024 samples) over
// the pixels fully on the model.
ImageComparison splitSumAgainstReference(const Scene& s, const Camera& cam, const Baked& b,
                                         RenderOptions o) {
  o.mode = RenderMode::SplitSum;
  o.spp = 1;
  const RenderResult split = renderScene(s, cam, b.result, b.options, o);
  o.mode = RenderMode::Reference;
  o.spp = 1024;
  const RenderResult ref = renderScene(s, cam, b.result, b.options, o);
  const auto mask = interiorMask(split, ref);
  return compareImages(split.color, ref.color, &mask);
}

glm::vec3 smoothSky(glm::vec3 d) {
  return glm::vec3(1.0f + 0.5f * d.z, 1.0f + 0.3f * d.x, 1.0f + 0.2f * d.y);
}

}  // namespace

TEST(Render, WhiteFurnace) {
  // Radiance 1 everywhere, a white metal sphere: the reference reflects its directional albedo
  // E(n.v) = A + B (single scattering loses energy); the split sum without compensation gives
  // the same, and with compensation it gives back the lost energy: 1.
  const Baked b = bakeOf([](glm::vec3) { return glm::vec3(1.0f); }, 32);
  const int n = 9;
  const Camera cam = sphereCamera(n);
  for (float r : {0.5f, 1.0f}) {
    const Scene s = sphere(glm::vec3(1.0f), 1.0f, r);
    RenderOptions o;
    o.mode = RenderMode::Reference;
    o.spp = 4096;
    const RenderResult ref = renderScene(s, cam, b.result, b.options, o);
    o.mode = RenderMode::SplitSum;
    o.spp = 1;
    const RenderResult compensated = renderScene(s, cam, b.result, b.options, o);
    o.multipleScattering = false;
    const RenderResult single = renderScene(s, cam, b.result, b.options, o);
    for (int x : {4, 6}) {  // the center (n.v = 1) and a pixel off to the side
      const float d = (x + 0.5f) / n * 2.0f - 1.0f;
      const float NoV = std::sqrt(1.0f - d * d);
      const glm::vec3 e = integrateDfg(NoV, r, 8192);
      EXPECT_NEAR(ref.color.at(x, 4).y, e.x + e.y, 0.02f) << "r " << r << " n.v " << NoV;
      EXPECT_NEAR(single.color.at(x, 4).y, e.x + e.y, 0.01f) << "r " << r << " n.v " << NoV;
      EXPECT_NEAR(compensated.color.at(x, 4).y, 1.0f, 0.01f) << "r " << r << " n.v " << NoV;
    }
    EXPECT_LT(ref.color.at(4, 4).y, 0.999f);  // single scattering really loses energy at r = 1
  }
}

TEST(Render, MirrorReflectsTheEnvironment) {
  const Baked b = bakeOf(smoothSky, 128);
  const int n = 9;
  const Camera cam = sphereCamera(n);
  const Scene s = sphere(glm::vec3(1.0f), 1.0f, 0.0f);
  RenderOptions o;
  o.spp = 1;
  for (auto mode : {RenderMode::SplitSum, RenderMode::Reference}) {
    o.mode = mode;
    o.spp = mode == RenderMode::Reference ? 64 : 1;
    const RenderResult img = renderScene(s, cam, b.result, b.options, o);
    for (int x : {4, 6}) {
      const float d = (x + 0.5f) / n * 2.0f - 1.0f;
      const glm::vec3 nrm(d, 0.0f, std::sqrt(1.0f - d * d));
      const glm::vec3 v(0, 0, 1);
      const glm::vec3 refl = 2.0f * glm::dot(nrm, v) * nrm - v;
      const glm::vec3 expected = smoothSky(refl);
      EXPECT_LT(maxRelativeError(img.color.at(x, 4), expected), 0.02) << int(mode) << " x " << x;
    }
  }
}

TEST(Render, LambertianAgreesInBothModes) {
  const Baked b = bakeOf(smoothSky);
  const Camera cam = sphereCamera(17);
  const Scene s = sphere(glm::vec3(0.5f), 0.0f, 1.0f);
  RenderOptions o;
  o.diffuse = DiffuseModel::Lambert;
  o.only = ShadingTerms::Diffuse;
  const ImageComparison c = splitSumAgainstReference(s, cam, b, o);
  EXPECT_GT(c.pixels, 150u);
  EXPECT_LT(c.overall.meanRelativeError, 0.01);
}

TEST(Render, SplitSumNearReferenceOnSmoothEnvironments) {
  const Baked b = bakeOf(smoothSky);
  const Camera cam = sphereCamera(17);
  for (float r : {0.3f, 0.7f}) {
    const Scene s = sphere(glm::vec3(0.9f, 0.6f, 0.3f), 0.5f, r);
    RenderOptions o;
    o.multipleScattering = false;  // the reference is single scattering
    const ImageComparison c = splitSumAgainstReference(s, cam, b, o);
    RecordProperty("mean_relative_error_r" + std::to_string(r),
                   std::to_string(c.overall.meanRelativeError));
    EXPECT_LT(c.overall.meanRelativeError, 0.03) << "r " << r;  // the split sum's own error
  }
}

TEST(Render, ReferenceIsReproducibleAndConverges) {
  const Baked b = bakeOf(smoothSky, 32);
  const Camera cam = sphereCamera(5);
  const Scene s = sphere(glm::vec3(0.8f), 0.0f, 0.4f);
  RenderOptions o;
  o.mode = RenderMode::Reference;
  o.spp = 64;
  EXPECT_EQ(renderScene(s, cam, b.result, b.options, o).color.pixels,
            renderScene(s, cam, b.result, b.options, o).color.pixels);
  o.noiseThreshold = 0.01f;
  o.spp = 1 << 16;
  const RenderResult adaptive = renderScene(s, cam, b.result, b.options, o);
  EXPECT_LT(adaptive.samples, 25.0 * (1 << 16));  // stopped early
}

TEST(Render, ShadowsDarkenTheReference) {
  // Two spheres side by side under a sky: with visibility, each hides part of the sky from
  // the other.
  const Baked b = bakeOf([](glm::vec3) { return glm::vec3(1.0f); }, 16);
  Scene s = makeSphereGrid(glm::vec3(0.8f), 2);
  Camera cam = sphereCamera(16);
  cam.orthoWidth = 8.0f;
  RenderOptions o;
  o.mode = RenderMode::Reference;
  o.spp = 64;
  const RenderResult open = renderScene(s, cam, b.result, b.options, o);
  o.shadows = true;
  const RenderResult shadowed = renderScene(s, cam, b.result, b.options, o);
  const auto sum = [](const RenderResult& r) {
    double total = 0.0;
    for (std::size_t i = 0; i < r.alpha.size(); ++i)
      if (r.alpha[i] == 1.0f) total += luminance(r.color.pixels[i]);
    return total;
  };
  EXPECT_LT(sum(shadowed), 0.97 * sum(open));
  EXPECT_GT(sum(shadowed), 0.5 * sum(open));
}

TEST(Camera, ExposureMath) {
  // Sunny 16: f/16, 1/100 s, ISO 100 is EV 14.6.
  EXPECT_NEAR(ev100FromSettings(16.0f, 0.01f, 100.0f), std::log2(25600.0f), 1e-5f);
  EXPECT_NEAR(ev100FromSettings(1.0f, 1.0f, 100.0f), 0.0f, 1e-6f);
  EXPECT_NEAR(ev100FromSettings(1.0f, 1.0f, 200.0f), -1.0f, 1e-6f);  // ISO doubles: one stop
  EXPECT_NEAR(exposureFromEv100(0.0f), 1.0f / 1.2f, 1e-7f);
  EXPECT_NEAR(exposureFromEv100(1.0f), 0.5f / 1.2f, 1e-7f);
  EXPECT_NEAR(ev100FromAverageLuminance(0.125f), 0.0f, 1e-6f);  // 12.5 / 100
  Image img(4, 4, glm::vec3(0.5f));
  EXPECT_NEAR(averageLogLuminance(img), 0.5f, 1e-3f);
}

TEST(Camera, RaysThroughPixelCenters) {
  Camera c;
  c.width = 4;
  c.height = 2;
  c.from = glm::vec3(0, 0, 3);
  const Ray center = c.generateRay(2.0f, 1.0f);
  EXPECT_LT(glm::distance(center.direction, glm::vec3(0, 0, -1)), 1e-6f);
  const Ray right = c.generateRay(4.0f, 1.0f);
  EXPECT_GT(right.direction.x, 0.0f);  // +X to the right when looking down -Z with +Y up
  EXPECT_GT(c.generateRay(2.0f, 0.0f).direction.y, 0.0f);  // row 0 at the top
  c.perspective = false;
  c.orthoWidth = 2.0f;
  EXPECT_NEAR(c.generateRay(4.0f, 1.0f).origin.x, 1.0f, 1e-6f);
}

TEST(Camera, ToneCurvesAndSrgbRoundTrip) {
  EXPECT_EQ(toneMap(glm::vec3(2.0f), ToneMap::None), glm::vec3(1.0f));
  EXPECT_NEAR(toneMap(glm::vec3(0.18f), ToneMap::Aces).x, 0.2669f, 1e-3f);
  EXPECT_LT(toneMap(glm::vec3(100.0f), ToneMap::Filmic).x, 1.0001f);
  for (float v = 0.0f; v <= 1.0f; v += 0.01f) EXPECT_NEAR(linearToSrgb(srgbToLinear(v)), v, 1e-5f);
}
