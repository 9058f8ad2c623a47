// The glTF material's texture rules (ibl/shared/material.h, through the renderer) against values
// computed independently of the code under test: sRGB base color, alpha modes, the
// metallic-roughness channels, emission, the normal map's frame. Each test fails if its rule
// changes.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/render/gltf.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/shared/material.h"
#include "support/gltf_writer.hpp"
#include "support/quadrature.hpp"
#include "support/synthetic_bake.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// One pixel looking at the center of a model from +Z, orthographic.
glm::vec3 centerPixel(const Scene& scene, const SyntheticBake& s, RenderOptions o) {
  Camera c;
  c.perspective = false;
  c.orthoWidth = 0.01f;
  c.from = glm::vec3(0.0f, 0.0f, 3.0f);
  c.width = c.height = 1;
  o.spp = o.mode == RenderMode::Reference ? 16 : 1;
  const RenderResult r = renderScene(scene, c, s.bake, s.options, o);
  EXPECT_EQ(r.alpha[0], 1.0f);
  return r.color.at(0, 0);
}

}  // namespace

// Base color textures are sRGB: code 128 is 0.2158605 linear, not 0.50196.
TEST(ShadingRules, BaseColorTexturesAreSrgbDecoded) {
  TempDir dir;
  QuadMaterial m;
  m.baseColorCodes = {128, 64, 255};
  m.metallicFactor = 0.0f;
  m.specularFactor = 0.0f;  // Lambertian: no layer takes its share (fresnel_mix)
  writeMaterialQuad(dir / "q.gltf", m);
  const SyntheticBake s = syntheticBake(
      2, [](int, glm::vec3) { return glm::vec3(0.0f); }, [](glm::vec3) { return glm::vec3(1.0f); },
      glm::vec3(1.0f, 0.0f, 1.0f), 8);
  RenderOptions o;
  o.only = ShadingTerms::Diffuse;
  o.diffuse = DiffuseModel::Lambert;
  const glm::vec3 c = centerPixel(loadGltf((dir / "q.gltf").string()), s, o);
  EXPECT_NEAR(c.x, 0.2158605f, 1e-5f);
  EXPECT_NEAR(c.y, 0.0512695f, 1e-5f);
  EXPECT_NEAR(c.z, 1.0f, 1e-5f);
}

// alphaMode (glTF 2.0 3.9.4): the fraction of a pixel's samples the quad covers. The quad fills
// an 8 x 8 view; its texture's left half has alpha code 0.3 x 255 = 77 (0.302), the right
// half 204 (0.8); the factor's alpha multiplies both.
TEST(ShadingRules, AlphaModesCoverAsTheSpecificationSays) {
  TempDir dir;
  const SyntheticBake s = syntheticBake(
      2, [](int, glm::vec3) { return glm::vec3(0.0f); }, [](glm::vec3) { return glm::vec3(1.0f); },
      glm::vec3(1.0f, 0.0f, 1.0f), 8);
  const auto coverage = [&](const QuadMaterial& m, int spp) {
    writeMaterialQuad(dir / "q.gltf", m);
    Camera c;
    c.perspective = false;
    c.orthoWidth = 1.9f;
    c.from = glm::vec3(0.0f, 0.0f, 3.0f);
    c.width = c.height = 8;
    RenderOptions o;
    o.spp = spp;
    const RenderResult r =
        renderScene(loadGltf((dir / "q.gltf").string()), c, s.bake, s.options, o);
    double left = 0.0, right = 0.0;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) (x < 4 ? left : right) += r.alpha[y * 8 + x] / 32.0;
    return std::pair{left, right};
  };
  QuadMaterial m;
  m.alphaCodes = {77, 204};
  m.alphaMode = "OPAQUE";  // alpha ignored
  EXPECT_EQ(coverage(m, 1), std::pair(1.0, 1.0));
  m.alphaMode = "MASK";  // cutoff 0.5: left cut out, right kept
  EXPECT_EQ(coverage(m, 1), std::pair(0.0, 1.0));
  m.alphaCutoff = 0.25f;
  EXPECT_EQ(coverage(m, 1), std::pair(1.0, 1.0));
  m.baseColorAlpha = 0.5f;  // 0.151 and 0.4 against 0.25
  EXPECT_EQ(coverage(m, 1), std::pair(0.0, 1.0));
  // BLEND: covered with probability alpha, 0.151 and 0.4 here (256 samples per pixel, 32 pixels
  // per half: a standard deviation under 0.005).
  m.alphaMode = "BLEND";
  const auto [left, right] = coverage(m, 256);
  EXPECT_NEAR(left, 0.5 * 77.0 / 255.0, 0.02);
  EXPECT_NEAR(right, 0.5 * 204.0 / 255.0, 0.02);
}

// COLOR_0 multiplies the base color and its alpha (glTF 2.0, 3.9.2 and 3.7.2.1). The quad's
// vertex colors follow a linear function of position, so whatever the triangulation the color at
// a point is that function there: Lambertian diffuse under a uniform white irradiance of 1 shows
// the base color factor times it, in both modes. The alpha against a MASK cutoff of 0.5: 0.3
// cuts the quad out, 0.8 keeps it.
TEST(ShadingRules, VertexColorsMultiplyTheBaseColorAndItsAlpha) {
  TempDir dir;
  QuadMaterial m;
  m.baseColorFactor = glm::vec3(0.8f, 0.5f, 1.0f);
  m.metallicFactor = 0.0f;
  m.specularFactor = 0.0f;  // Lambertian: no layer takes its share (fresnel_mix)
  writeMaterialQuad(dir / "q.gltf", m);
  Scene scene = loadGltf((dir / "q.gltf").string());
  const auto field = [](glm::vec3 p) {
    return glm::vec4(0.5f + 0.2f * p.x, 0.5f - 0.15f * p.y, 0.25f + 0.1f * (p.x + p.y), 1.0f);
  };
  Mesh& mesh = scene.meshes.at(0);
  mesh.colors.clear();
  for (const glm::vec3& p : mesh.positions) mesh.colors.push_back(field(p));
  // A white environment of radiance 1: the reference's source, the split sum's irradiance.
  SyntheticBake s = syntheticBake(
      2, [](int, glm::vec3) { return glm::vec3(1.0f); }, [](glm::vec3) { return glm::vec3(1.0f); },
      glm::vec3(1.0f, 0.0f, 1.0f), 8);
  s.bake.source = cubeFromFunction(8, [](glm::vec3) { return glm::vec3(1.0f); });
  for (RenderMode mode : {RenderMode::SplitSum, RenderMode::Reference})
    for (glm::vec2 at : {glm::vec2(0.0f), glm::vec2(0.6f, -0.35f)}) {
      Camera c;
      c.perspective = false;
      c.orthoWidth = 0.01f;
      c.from = glm::vec3(at, 3.0f);
      c.at = glm::vec3(at, 0.0f);
      c.width = c.height = 1;
      RenderOptions o;
      o.mode = mode;
      o.spp = mode == RenderMode::Reference ? 256 : 1;
      o.only = ShadingTerms::Diffuse;
      o.diffuse = DiffuseModel::Lambert;
      const RenderResult r = renderScene(scene, c, s.bake, s.options, o);
      const glm::vec3 expected = m.baseColorFactor * glm::vec3(field(glm::vec3(at, 0.0f)));
      // The reference's estimate is exact but for its samples' noise (1 % here).
      const float relative = mode == RenderMode::Reference ? 1e-2f : 1e-4f;
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(r.color.at(0, 0)[k], expected[k], relative * expected[k])
            << "mode " << static_cast<int>(mode) << " at " << at.x << ", " << at.y << " channel "
            << k;
    }
  scene.materials.at(0).alphaMode = AlphaMode::Mask;
  for (float alpha : {0.3f, 0.8f}) {
    for (glm::vec4& color : mesh.colors) color.w = alpha;
    RenderOptions o;
    o.only = ShadingTerms::Diffuse;
    Camera c;
    c.perspective = false;
    c.orthoWidth = 0.01f;
    c.from = glm::vec3(0.0f, 0.0f, 3.0f);
    c.width = c.height = 1;
    for (RenderMode mode : {RenderMode::SplitSum, RenderMode::Reference}) {
      o.mode = mode;
      EXPECT_EQ(renderScene(scene, c, s.bake, s.options, o).alpha[0], alpha < 0.5f ? 0.0f : 1.0f)
          << "alpha " << alpha << " mode " << static_cast<int>(mode);
    }
  }
}

// metallicRoughnessTexture: roughness in G, metalness in B (linear), R ignored.
TEST(ShadingRules, MetallicRoughnessChannels) {
  TempDir dir;
  QuadMaterial m;
  m.metallicRoughnessCodes = {200, 64, 255};
  writeMaterialQuad(dir / "q.gltf", m);
  const SyntheticBake s = syntheticBake(
      6, [](int level, glm::vec3) { return glm::vec3(static_cast<float>(level)); },
      [](glm::vec3) { return glm::vec3(1.0f); }, glm::vec3(1.0f, 0.0f, 1.0f), 8);
  RenderOptions o;
  o.dominantDirections = false;
  // Metal (B = 1): no diffuse, specular = level read = roughness (64 / 255) x 5.
  EXPECT_NEAR(centerPixel(loadGltf((dir / "q.gltf").string()), s, o).x, 64.0f / 255.0f * 5.0f,
              1e-4f);
  m.metallicRoughnessCodes = {200, 255, 51};  // rough (level 5), metalness 0.2
  writeMaterialQuad(dir / "q.gltf", m);
  // specular 5 x F0 (0.04 + 0.96 x 0.2) + diffuse (1 - 0.2) x 1 x what fresnel_mix leaves of it
  // head-on under uniform light, 1 - 0.04 (the Schlick term's mean vanishes at n.v = 1).
  EXPECT_NEAR(centerPixel(loadGltf((dir / "q.gltf").string()), s, o).x,
              5.0f * (0.04f + 0.96f * 0.2f) + 0.8f * 0.96f, 1e-4f);
}

// KHR_materials_specular's textures: specularTexture's A multiplies specularFactor,
// specularColorTexture's RGB (sRGB) multiplies specularColorFactor, and with KHR_materials_ior
// they make F0 = min(((ior - 1) / (ior + 1))^2 color, 1) specular and F90 = specular, which the
// split sum weighs by the DFG table's A and B (here the constants 0.7 and 0.2).
TEST(ShadingRules, SpecularTexturesScaleTheDielectricsFresnel) {
  TempDir dir;
  writeMaterialQuad(dir / "q.gltf", specularLayerQuad(glm::vec3(0.0f)));
  const SyntheticBake s = syntheticBake(
      2, [](int, glm::vec3) { return glm::vec3(1.0f); }, [](glm::vec3) { return glm::vec3(0.0f); },
      glm::vec3(0.7f, 0.2f, 1.0f), 8);
  RenderOptions o;
  o.only = ShadingTerms::Specular;
  o.multipleScattering = MultipleScattering::Off;
  const glm::vec3 c = centerPixel(loadGltf((dir / "q.gltf").string()), s, o);
  const float specular = 0.8f * 128.0f / 255.0f, r0 = 1.0f / 9.0f;      // ((2 - 1) / (2 + 1))^2
  const glm::vec3 color(1.0f, 2.0f * 0.2158605f, 200.0f * 0.0512695f);  // sRGB 128, 64
  for (int k = 0; k < 3; ++k) {
    const float f0 = std::min(r0 * color[k], 1.0f) * specular;  // blue: clamped
    EXPECT_NEAR(c[k], 0.7f * f0 + 0.2f * specular, 1e-4f) << k;
  }
}

// KHR_materials_unlit: the quad shows baseColorFactor times its sRGB-decoded texture whatever
// lights it (a bright environment and a sun here), in both modes; its other properties (a
// rough white metal) reflect nothing. With vertex colors (COLOR_0), their product too: the
// colors are linear in position, so the quad's center shows their value there.
TEST(ShadingRules, UnlitShowsItsBaseColor) {
  TempDir dir;
  QuadMaterial m;
  m.baseColorFactor = glm::vec3(0.5f, 1.0f, 0.25f);
  m.baseColorCodes = {128, 64, 255};
  m.metallicFactor = 1.0f;
  m.roughnessFactor = 0.5f;
  m.unlit = true;
  writeMaterialQuad(dir / "q.gltf", m);
  Scene scene = loadGltf((dir / "q.gltf").string());
  Light sun;
  sun.type = LightType::Sun;
  sun.direction = glm::vec3(0.0f, 0.0f, 1.0f);  // toward the sun, in front of the quad
  sun.intensity = 100.0f;
  scene.lights.push_back(sun);
  const SyntheticBake s = syntheticBake(
      2, [](int, glm::vec3) { return glm::vec3(3.0f); }, [](glm::vec3) { return glm::vec3(3.0f); },
      glm::vec3(0.7f, 0.2f, 1.0f), 8);
  const glm::vec3 expected(0.5f * 0.2158605f, 1.0f * 0.0512695f, 0.25f * 1.0f);
  const glm::vec4 center(0.6f, 0.3f, 0.9f, 1.0f);
  for (bool colors : {false, true}) {
    if (colors)
      for (const glm::vec3& p : scene.meshes.at(0).positions)
        scene.meshes.at(0).colors.push_back(center +
                                            glm::vec4(0.3f * p.x, -0.2f * p.y, 0.0f, 0.0f));
    for (RenderMode mode : {RenderMode::SplitSum, RenderMode::Reference}) {
      RenderOptions o;
      o.mode = mode;
      const glm::vec3 c = centerPixel(scene, s, o);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(c[k], expected[k] * (colors ? center[k] : 1.0f), 1e-4f)
            << k << (colors ? " with vertex colors" : "");
    }
  }
}

// Emission: emissiveFactor times the sRGB-decoded emissiveTexture, in both modes, added to the
// reflected light (none here: a black environment).
TEST(ShadingRules, Emission) {
  TempDir dir;
  QuadMaterial m;
  m.emissiveFactor = {1.0f, 0.5f, 0.25f};
  m.emissiveCodes = {128, 128, 255};
  writeMaterialQuad(dir / "q.gltf", m);
  const Scene scene = loadGltf((dir / "q.gltf").string());
  SyntheticBake s = syntheticBake(
      2, [](int, glm::vec3) { return glm::vec3(0.0f); }, [](glm::vec3) { return glm::vec3(0.0f); },
      glm::vec3(1.0f, 0.0f, 1.0f), 8);
  for (auto mode : {RenderMode::SplitSum, RenderMode::Reference}) {
    RenderOptions o;
    o.mode = mode;
    const glm::vec3 c = centerPixel(scene, s, o);
    EXPECT_NEAR(c.x, 0.2158605f, 1e-5f);
    EXPECT_NEAR(c.y, 0.5f * 0.2158605f, 1e-5f);
    EXPECT_NEAR(c.z, 0.25f, 1e-5f);
  }
}

// The normal map's frame: tangent T, bitangent B = (N x T) w. A texel tilting the normal 45
// degrees toward +B makes a mirror seen from +Z reflect straight up (B = +Y here), or straight
// down when the tangent's w is -1.
TEST(ShadingRules, NormalMapBitangentSign) {
  TempDir dir;
  const SyntheticBake s = syntheticBake(
      2, [](int, glm::vec3 d) { return d + glm::vec3(2.0f); },
      [](glm::vec3) { return glm::vec3(0.0f); }, glm::vec3(1.0f, 0.0f, 1.0f));
  for (float w : {1.0f, -1.0f}) {
    QuadMaterial m;
    m.roughnessFactor = 0.0f;
    m.normalCodes = {128, 218, 218};  // (0, 0.71, 0.71) in tangent space
    m.tangent = {1.0f, 0.0f, 0.0f, w};
    writeMaterialQuad(dir / "q.gltf", m);
    RenderOptions o;
    o.only = ShadingTerms::Specular;
    const glm::vec3 r = decodeDirection(centerPixel(loadGltf((dir / "q.gltf").string()), s, o));
    EXPECT_NEAR(r.y, w, 0.01f) << "w = " << w;
    EXPECT_NEAR(r.x, 0.0f, 0.02f);
  }
}

// KHR_materials_ior: F0 is Fresnel's reflectance at normal incidence (the s and p equations at
// 0.001 rad, not the formula), 1 for ior 0 (the specular-glossiness mode); the specular layer
// scales the dielectric alone, its color clamped before the factor, and metallic mixes.
TEST(Reflectance, DielectricF0IsFresnelsAtNormalIncidence) {
  for (float ior : {1.0f, 1.33f, 1.5f, 1.76f, 2.42f, 4.0f})
    EXPECT_NEAR(shared::dielectricF0FromIor(ior), fresnelDielectric(std::cos(1e-3), ior), 1e-6)
        << ior;
  EXPECT_FLOAT_EQ(shared::dielectricF0FromIor(0.0f), 1.0f);
  const shared::SpecularReflectance r = shared::specularReflectance(
      glm::vec3(0.9f, 0.5f, 0.1f), 0.25f, 1.5f, 0.5f, glm::vec3(1.0f, 0.5f, 50.0f), false);
  const glm::vec3 dielectric(0.04f * 0.5f, 0.02f * 0.5f, 1.0f * 0.5f);  // 0.04 x 50 clamped
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(r.f0[k], 0.75f * dielectric[k] + 0.25f * glm::vec3(0.9f, 0.5f, 0.1f)[k], 1e-6f);
  EXPECT_NEAR(r.f90, 0.75f * 0.5f + 0.25f, 1e-6f);
}

// glTF's fresnel_mix takes from the diffuse what the specular layer reflects at the light's half
// vector; the split sum, which has no light direction, takes its mean over a Lambertian lobe,
// through lambertianSchlickMean: the cosine-weighted mean of (1 - v.h)^5, here by the midpoint
// rule over (sin^2 theta, phi), within 6e-4 of the fit from n.v = 0 to 1. A fit of exponent 2
// instead of 2.55 is 2e-3 off.
TEST(ShadingRules, LambertianSchlickMeanIsTheCosineWeightedMean) {
  for (double NoV : {0.02, 0.1, 0.25, 0.4, 0.55, 0.7, 0.85, 1.0})
    EXPECT_NEAR(shared::lambertianSchlickMean(static_cast<float>(NoV)),
                lambertianSchlickMeanQuadrature(NoV), 6e-4)
        << "n.v " << NoV;
}
