// KHR_materials_clearcoat in both render modes, against computations written apart from the
// code under test: the specification's layering f = (1 - c Fc) f_below + c Fc f_coat with Fc =
// Schlick's Fresnel of IOR 1.5 at n.v (written out here), the coat's GGX lobe by quadrature
// (tests/support/quadrature.hpp, from Walter and Heitz) and in closed form under a point light,
// the emission darkened by the coat, energy conservation in a white furnace, and glTF files
// carrying every part of the extension (factors, textures, the coat's own normal map) into the
// renderer and `ibl info`.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../../src/render/ray_tracer.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/render/renderer.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/material_quads.hpp"
#include "support/quadrature.hpp"
#include "support/sphere_renders.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// The specification's coat Fresnel: f0 = ((1 - 1.5) / (1 + 1.5))^2 = 0.04, Schlick's curve.
double coatFresnel(double NoV) {
  return 0.04 + 0.96 * std::pow(1.0 - NoV, 5.0);
}

const Baked& coatFurnace() {
  static const Baked b = bakeOf([](glm::vec3) { return glm::vec3(1.0f); }, 32);
  return b;
}

// A sphere of base color `base` with no specular layer of its own (specular 0, so that only the
// coat reflects), under a coat of strength `clearcoat` and roughness `coatRoughness`.
Scene coatedSphere(glm::vec3 base, float clearcoat, float coatRoughness,
                   glm::vec3 emissive = glm::vec3(0.0f)) {
  Material m;
  m.baseColor = base;
  m.metallic = 0.0f;
  m.roughness = 0.5f;
  m.specular = 0.0f;
  m.emissive = emissive;
  m.clearcoat = clearcoat;
  m.clearcoatRoughness = coatRoughness;
  return makeSphereScene(m);
}

// The unit sphere at n.v = 1, 0.75, 0.5 and 0.25, each seen head-on through a one-pixel
// orthographic view 0.002 wide (so that the pixel holds one n.v), in both modes.
constexpr double kViews[] = {1.0, 0.75, 0.5, 0.25};
struct Views {
  double split[4], reference[4];
};
Views renderViews(const Scene& s, RenderOptions o, int referenceSpp) {
  const Baked& b = coatFurnace();
  Views r{};
  for (int i = 0; i < 4; ++i) {
    Camera c = sphereCamera(1);
    c.orthoWidth = 0.002f;
    const float x = static_cast<float>(std::sqrt(1.0 - kViews[i] * kViews[i]));
    c.from = glm::vec3(x, 0.0f, 5.0f);
    c.at = glm::vec3(x, 0.0f, 0.0f);
    RenderOptions split = o;
    split.spp = 1;
    r.split[i] = renderScene(s, c, b.result, b.options, split).color.at(0, 0).y;
    RenderOptions reference = o;
    reference.mode = RenderMode::Reference;
    reference.spp = referenceSpp;
    r.reference[i] = renderScene(s, c, b.result, b.options, reference).color.at(0, 0).y;
  }
  return r;
}

}  // namespace

// A coat over a black base in a white furnace reflects c Fc(n.v) times its GGX lobe's albedo
// with F = 1 (the lobe carries no Fresnel of its own): quadrature, across the sphere.
TEST(ClearcoatRender, CoatReflectsItsWeightedGgxLobe) {
  const float clearcoat = 0.8f, coatRoughness = 0.4f;
  RenderOptions o;
  o.multipleScattering = MultipleScattering::Off;
  const Views r = renderViews(coatedSphere(glm::vec3(0.0f), clearcoat, coatRoughness), o, 4096);
  double worstSplit = 0.0, worstRef = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double NoV = kViews[i];
    const double e = clearcoat * coatFresnel(NoV) * ggxAlbedoQuadrature(NoV, coatRoughness, 1, 1);
    EXPECT_NEAR(r.split[i], e, 0.01 * e) << "split sum, n.v " << NoV;
    EXPECT_NEAR(r.reference[i], e, 0.01 * e) << "reference, n.v " << NoV;
    worstSplit = std::max(worstSplit, std::abs(r.split[i] / e - 1.0));
    worstRef = std::max(worstRef, std::abs(r.reference[i] / e - 1.0));
  }
  std::printf("coat lobe against quadrature: split sum within %.2f %%, reference %.2f %%\n",
              100.0 * worstSplit, 100.0 * worstRef);
}

// A white Lambertian base under a full coat in a white furnace: what the coat reflects plus what
// it lets through of the base, (1 - Fc) + Fc E_coat, below 1 (no energy created). Without the
// coat's attenuation of the base the sum would exceed 1. The reference samples the coat by the
// BRDF's mixture, and with the microfacet walk by one lobe at a time: both agree.
TEST(ClearcoatRender, CoatAttenuatesTheBaseAndConservesEnergy) {
  const float coatRoughness = 0.3f;
  for (MultipleScattering ms : {MultipleScattering::Off, MultipleScattering::Walk}) {
    RenderOptions o;
    o.diffuse = DiffuseModel::Lambert;
    o.multipleScattering = ms;
    const Views r = renderViews(coatedSphere(glm::vec3(1.0f), 1.0f, coatRoughness), o, 1024);
    const char* mode = ms == MultipleScattering::Walk ? ", the walk" : "";
    for (int i = 0; i < 4; ++i) {
      const double NoV = kViews[i], fc = coatFresnel(NoV);
      const double e = (1.0 - fc) + fc * ggxAlbedoQuadrature(NoV, coatRoughness, 1, 1);
      EXPECT_LT(e, 1.0);
      EXPECT_NEAR(r.split[i], e, 0.01 * e) << "split sum, n.v " << NoV << mode;
      EXPECT_NEAR(r.reference[i], e, 0.02 * e) << "reference, n.v " << NoV << mode;
      EXPECT_LT(r.split[i], 1.0);
    }
  }
}

// The coat lies over the emission (the specification's "Emission"): an emitter of radiance 1
// under a coat of strength 0.5, in the dark, shows 1 - 0.5 Fc(n.v) in both modes.
TEST(ClearcoatRender, CoatDarkensTheEmission) {
  RenderOptions o;
  o.environmentLight = false;
  const Views r = renderViews(coatedSphere(glm::vec3(0.0f), 0.5f, 0.2f, glm::vec3(1.0f)), o, 16);
  for (int i = 0; i < 4; ++i) {
    const double e = 1.0 - 0.5 * coatFresnel(kViews[i]);
    EXPECT_NEAR(r.split[i], e, 1e-3) << "split sum, n.v " << kViews[i];
    EXPECT_NEAR(r.reference[i], e, 1e-3) << "reference, n.v " << kViews[i];
  }
}

// Under a point light the coat's lobe is GGX in closed form: E c Fc(n.v) D(h) G2 / (4 n.v n.l)
// n.l, E = I / d^2 (the light 10 units away, 35 degrees off the view), both modes.
TEST(ClearcoatRender, PointLightOnTheCoatIsItsGgxLobe) {
  const float coatRoughness = 0.35f, clearcoat = 1.0f;
  Scene s = coatedSphere(glm::vec3(0.0f), clearcoat, coatRoughness);
  const double theta = 35.0 * 3.14159265358979323846 / 180.0;
  const glm::dvec3 l(std::sin(theta), 0.0, std::cos(theta)), v(0.0, 0.0, 1.0);
  Light light;
  light.type = LightType::Point;
  light.position = glm::vec3(0.0f, 0.0f, 1.0f) + 10.0f * glm::vec3(l);
  light.intensity = 100.0f;  // 1 lx at the point, facing the light
  s.lights.push_back(light);
  const double alpha = coatRoughness * coatRoughness, NoL = l.z;
  const glm::dvec3 h = glm::normalize(v + l);
  const double g2 = 1.0 / (1.0 + ggxLambdaFromPaper(1.0, alpha) + ggxLambdaFromPaper(NoL, alpha));
  const double expected =
      clearcoat * coatFresnel(1.0) * ggxDistributionFromPaper(h.z, alpha) * g2 / (4.0 * NoL) * NoL;
  RenderOptions o;
  o.environmentLight = false;
  o.spp = 1;
  Camera c = sphereCamera(1);
  c.orthoWidth = 0.02f;
  const Baked& b = coatFurnace();
  const float split = renderScene(s, c, b.result, b.options, o).color.at(0, 0).y;
  o.mode = RenderMode::Reference;
  o.spp = 16;
  const float ref = renderScene(s, c, b.result, b.options, o).color.at(0, 0).y;
  EXPECT_NEAR(split, expected, 0.01 * expected);
  EXPECT_NEAR(ref, expected, 0.01 * expected);
  std::printf("point light on the coat: closed form %.6f, split sum %.6f, reference %.6f\n",
              expected, split, ref);
}

// glTF carries every part of the extension: the factors times their textures' R and G, and the
// coat's own normal map, which the base's does not bend (without one, the coat follows the
// interpolated normal); `ibl info` reports the coat; forbidden values are refused.
TEST(ClearcoatRender, GltfCarriesTheCoatAndItsTextures) {
  TempDir dir;
  QuadMaterial q;
  q.metallicFactor = 0.0f;
  q.clearcoatFactor = 0.9f;
  q.clearcoatRoughnessFactor = 0.6f;
  q.clearcoatCodes = {128, 64, 0};  // R 128 / 255 of the factor, G 64 / 255 of the roughness
  q.normalCodes = {218, 128, 218};  // the base's normal leans toward +X
  writeMaterialQuad(dir / "coat.gltf", q);
  q.clearcoatNormalCodes = {38, 128, 218};  // the coat's toward -X
  q.clearcoatNormalScale = 0.5f;
  writeMaterialQuad(dir / "coat_normal.gltf", q);

  const SurfacePoint p = quadSurface(loadGltf((dir / "coat.gltf").string()));
  EXPECT_NEAR(p.clearcoat, 0.9f * 128.0f / 255.0f, 1e-5f);
  EXPECT_NEAR(p.clearcoatRoughness, 0.6f * 64.0f / 255.0f, 1e-5f);
  EXPECT_GT(p.normal.x, 0.3f);  // the base's map bends the base's normal
  EXPECT_NEAR(p.clearcoatNormal.z, 1.0f, 1e-5f) << "the coat follows the unmapped normal";
  const SurfacePoint q2 = quadSurface(loadGltf((dir / "coat_normal.gltf").string()));
  // The coat's texel (-0.7, 0, 0.71) with X scaled by 0.5, normalized.
  const glm::vec3 ts((38.0f / 255.0f * 2.0f - 1.0f) * 0.5f, 128.0f / 255.0f * 2.0f - 1.0f,
                     218.0f / 255.0f * 2.0f - 1.0f);
  EXPECT_NEAR(q2.clearcoatNormal.x, glm::normalize(ts).x, 1e-4f);
  EXPECT_NEAR(q2.normal.x, p.normal.x, 1e-6f) << "the coat's map leaves the base's normal";

  const CliRun info = runIbl("info " + quote(dir / "coat.gltf") + " --json");
  ASSERT_EQ(info.status, 0) << info.output;
  const nlohmann::json j = nlohmann::json::parse(info.output);
  EXPECT_NEAR(j["materials"][0]["clearcoat"].get<double>(), 0.9, 1e-6);
  EXPECT_NEAR(j["materials"][0]["clearcoat_roughness"].get<double>(), 0.6, 1e-6);

  expectExtensionRefused(
      dir / "coat.gltf", "KHR_materials_clearcoat",
      {{R"({"clearcoatFactor": 1.5})", "KHR_materials_clearcoat clearcoatFactor: 1.5"},
       {R"({"clearcoatRoughnessFactor": -0.1})", "clearcoatRoughnessFactor: -0.1"},
       {R"({"clearcoatFactor": "thick"})", "clearcoatFactor: not a number"}});
}
