// The scene on the viewer's device (src/gpu/scene_upload.cpp) as the CPU split sum reads it:
// local probes, IES profiles' tables, the sheen's chain and table, textured and compressed
// meshes (their mip chains, sRGB formats, samplers, UV sets and alpha masks). Like the other GPU
// tests, these fail without a Vulkan device.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ibl/bake/dfg.hpp"
#include "ibl/gpu/viewer.hpp"
#include "ibl/io/ies.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/shared/material.h"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/light_scenes.hpp"
#include "support/probe_capture.hpp"
#include "support/viewer_comparison.hpp"

using namespace ibl;
using namespace ibl::test;
using namespace ibl::test::viewer;

// Local probes: three probes of the sphere grid (box proxies and influences of different sizes
// overlapping with fades, a sphere proxy and influence), composed and parallax-corrected with
// distance-based roughness by the viewer's shader (ibl/shared/probes.h) as by the CPU's
// lookupProbes; with parallax off too.
TEST(Viewer, ProbesMatchTheCpu) {
  const Scene scene = makeSphereGrid(glm::vec3(0.8f, 0.6f, 0.4f));
  const Baked& b = sunsetBake();
  CaptureOptions capture;
  capture.size = 32;
  capture.spp = 4;
  capture.bounces = 1;
  const auto probeAt = [&](glm::vec3 at, ProbeVolume proxy, ProbeVolume influence, float fade) {
    return captureAndBakeProbe(scene, b.bake, b.options, placementAt(at, proxy, influence, fade),
                               capture);
  };
  std::vector<LocalProbe> probes = {
      probeAt({-2.5f, 0.0f, 1.5f}, boxVolume({-9, -4, -3}, {9, 4, 3}, {0, 20, 0}),
              boxVolume({-6, -3, -2}, {1, 3, 2}), 1.0f),
      probeAt({2.5f, 0.0f, 1.5f}, sphereVolume({1, 0, 0}, 8.0f), sphereVolume({3, 0, 0}, 4.0f),
              1.5f),
      probeAt({0.0f, 0.0f, 2.0f}, boxVolume({-9, -4, -3}, {9, 4, 3}),
              boxVolume({-8, -3, -3}, {8, 3, 3}), 2.0f)};
  std::stable_sort(probes.begin(), probes.end(), [](const LocalProbe& x, const LocalProbe& y) {
    return volumeSize(x.placement.influence) < volumeSize(y.placement.influence);
  });
  gpu::SceneRenderer viewer(graphicsContext(), scene, b.bake, b.options, probes);
  RenderOptions o;
  o.spp = 1;
  o.probes = &probes;
  const Camera camera = lookingAt({0, 0, 20}, 320, 160);
  for (bool parallax : {true, false}) {
    o.parallaxCorrection = parallax;
    const RenderResult g = viewer.render(camera, o);
    const RenderResult c = renderScene(scene, camera, b.bake, b.options, o);
    const Comparison cmp = compare(g, c);
    std::printf("probes, parallax %d: mean %.5f, over 1 %% %.4f\n", parallax, cmp.meanRelative,
                cmp.fractionOver1);
    // Measured: mean 0.003 %, 0.05 % of the pixels over 1 %; the shader without distance-based
    // roughness: 0.12 % and 1.5 %.
    EXPECT_LT(cmp.meanRelative, 3e-4) << parallax;
    EXPECT_LT(cmp.fractionOver1, 5e-3) << parallax;
  }
}

// IES profiles shade the grid as on the CPU: the viewer's table (2 x 5 degrees, bilinear)
// against the CPU's interpolation over the photometric web, for a profile that varies with both
// angles, on a point light (nadir -Y) and a tilted spot (nadir along its direction).
TEST(Viewer, IesProfilesMatchTheCpu) {
  const auto profile =
      std::make_shared<const IesProfile>(parseIes(test::asymmetricIesText(), "viewer.ies"));
  Scene scene = makeSphereGrid(glm::vec3(0.8f, 0.6f, 0.4f));
  Light point = viewerTestLight(LightType::Point, {-3, 5, 3}, {0, -1, 0}, 1.0f, 1.0f);
  point.ies = profile;
  Light spot = viewerTestLight(LightType::Spot, {4, 3, 5}, {-0.5f, -0.4f, -0.8f}, 1.0f, 1.0f);
  spot.outerAngle = glm::radians(80.0f);
  spot.innerAngle = glm::radians(70.0f);
  spot.ies = profile;
  checkLight(point);
  checkLight(spot);
  scene.lights = {point, spot};
  const Comparison c = renderLitByLightsAlone(scene);
  // Measured: mean 0.003 %, 0.004 % of the pixels over 1 %; the table read with the horizontal
  // angle mirrored: 2.8 %.
  EXPECT_LT(c.meanRelative, 1e-3);
  EXPECT_LT(c.fractionOver1, 1e-2);
}

// KHR_materials_sheen: the sheen layer over a dielectric, under the environment alone and with a
// point light, and the sheen alone (--only sheen), as the CPU's split sum shades it.
TEST(Viewer, SheenMatchesTheCpu) {
  static const Baked sheenBake = bakeSunset(true);
  Material m;
  m.baseColor = glm::vec3(0.2f, 0.3f, 0.6f);
  m.roughness = 0.6f;
  m.sheenColor = glm::vec3(0.9f, 0.7f, 0.5f);
  m.sheenRoughness = 0.4f;
  Scene scene = makeSphereScene(m);
  const Camera camera = lookingAt({0.5f, 1.0f, 4.0f}, 96, 96);
  RenderOptions o;
  o.spp = 1;
  for (ShadingTerms only : {ShadingTerms::Both, ShadingTerms::Sheen}) {
    o.only = only;
    const Comparison c = renderBoth(scene, camera, o, 0.0f, sheenBake);
    std::printf("sheen sphere, viewer vs CPU (only %d): %.2e\n", static_cast<int>(only),
                c.meanRelative);
    EXPECT_LT(c.meanRelative, 1e-3) << static_cast<int>(only);
    EXPECT_LT(c.coverageMismatch, 5e-3) << static_cast<int>(only);
  }
  Light l = viewerTestLight(LightType::Point, {2, 3, 3}, {0, -1, 0}, 200.0f, 1.0f);
  scene.lights.push_back(l);
  o.only = ShadingTerms::Both;
  const Comparison lit = renderBoth(scene, camera, o, 0.0f, sheenBake);
  std::printf("sheen sphere and a point light, viewer vs CPU: %.2e\n", lit.meanRelative);
  EXPECT_LT(lit.meanRelative, 1e-3);
  // At a sheen roughness of 0.15 the lights' lobe takes the tabulated exact Lambda over most
  // angles: the frame's buffer against the header's array.
  Scene smooth = scene;
  smooth.materials[0].sheenRoughness = 0.15f;
  const Comparison tabulated = renderBoth(smooth, camera, o, 0.0f, sheenBake);
  std::printf("sheen of roughness 0.15 and a point light, viewer vs CPU: %.2e\n",
              tabulated.meanRelative);
  EXPECT_LT(tabulated.meanRelative, 1e-3);
  // Neubelt's visibility, named: its table in place of the bake's and the lights' lobe through
  // the frame's uniforms; a lobe that contradicts the table is refused.
  Baked neubelt = sheenBake;
  neubelt.options.sheenVisibility = SheenVisibility::Neubelt;
  neubelt.bake.sheenDfg =
      integrateSheenDfgLut(neubelt.options.dfgSize, neubelt.options.dfgSize,
                           4 * neubelt.options.dfgSamples, SheenVisibility::Neubelt);
  o.sheenVisibility = SheenVisibility::Neubelt;
  const Comparison named = renderBoth(scene, camera, o, 0.0f, neubelt);
  std::printf("Neubelt sheen sphere and a point light, viewer vs CPU: %.2e\n", named.meanRelative);
  EXPECT_LT(named.meanRelative, 1e-3);
  o.sheenVisibility = SheenVisibility::Charlie;
  try {
    gpu::SceneRenderer viewer(graphicsContext(), scene, neubelt.bake, neubelt.options);
    viewer.render(camera, o);
    ADD_FAILURE() << "a Charlie lobe was drawn with a Neubelt table";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("neubelt"), std::string::npos) << e.what();
  }
  // A sheen without the bake's sheen chain is refused, as `ibl render` refuses it.
  try {
    gpu::SceneRenderer viewer(graphicsContext(), scene, sunsetBake().bake, sunsetBake().options);
    ADD_FAILURE() << "a sheen material was drawn without a sheen bake";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--sheen"), std::string::npos) << e.what();
  }
}

// KHR_materials_ior and KHR_materials_specular: factors and textures on a quad, and a grid of
// colored specular layers under the environment and a point light.
TEST(Viewer, IorAndSpecularMatchTheCpu) {
  TempDir dir;
  QuadMaterial m = specularLayerQuad(glm::vec3(0.3f));
  m.roughnessFactor = 0.3f;
  writeMaterialQuad(dir / "specular.gltf", m);
  RenderOptions o;
  o.spp = 1;
  Comparison c = renderBoth(loadGltf((dir / "specular.gltf").string()),
                            lookingAt({0.3f, 0.2f, 3.0f}, 64, 64), o);
  EXPECT_LT(c.meanRelative, 1e-3);
  Material base;
  base.baseColor = glm::vec3(0.5f, 0.3f, 0.2f);
  base.ior = 1.33f;
  base.specular = 0.6f;
  base.specularColor = glm::vec3(1.0f, 0.5f, 4.0f);
  Scene grid = makeSphereGrid(base);
  Light l = viewerTestLight(LightType::Point, {-6, 9, 4}, {0, -1, 0}, 2000.0f, 1.0f);
  l.range = 30.0f;
  grid.lights.push_back(l);
  c = renderBoth(grid, lookingAt({0, 0, 20}, 320, 160), o);
  EXPECT_LT(c.meanRelative, 1e-3);
  EXPECT_LT(c.fractionOver1, 5e-3);
}

namespace {

// The sphere grid of `base` under a point light and a sphere light (whose LTC lookups a layer's
// lobes take), for the material extensions' comparisons.
Scene gridUnderPointAndSphereLights(const Material& base) {
  Scene grid = makeSphereGrid(base);
  Light l = viewerTestLight(LightType::Point, {-6, 9, 4}, {0, -1, 0}, 2000.0f, 1.0f);
  l.range = 30.0f;
  grid.lights.push_back(l);
  Light sphere = viewerTestLight(LightType::Sphere, {5, 6, 6}, {0, -1, 0}, 3000.0f, 1.0f);
  sphere.radius = 0.8f;
  grid.lights.push_back(sphere);
  return grid;
}

}  // namespace

// KHR_materials_clearcoat: a quad with every part of the extension (factor and roughness
// textures, the coat's own normal map over the base's), and a coated grid under a point light
// and a sphere light (the coat's own LTC lookup).
TEST(Viewer, ClearcoatMatchesTheCpu) {
  TempDir dir;
  QuadMaterial m;
  m.baseColorFactor = glm::vec3(0.5f, 0.1f, 0.05f);
  m.metallicFactor = 0.0f;
  m.roughnessFactor = 0.6f;
  m.normalCodes = {200, 128, 220};
  m.clearcoatFactor = 1.0f;
  m.clearcoatRoughnessFactor = 0.5f;
  m.clearcoatCodes = {200, 100, 0};
  m.clearcoatNormalCodes = {60, 150, 220};
  m.clearcoatNormalScale = 0.8f;
  writeMaterialQuad(dir / "coat.gltf", m);
  RenderOptions o;
  o.spp = 1;
  Comparison c =
      renderBoth(loadGltf((dir / "coat.gltf").string()), lookingAt({0.3f, 0.2f, 3.0f}, 64, 64), o);
  EXPECT_LT(c.meanRelative, 1e-3);
  Material base;
  base.baseColor = glm::vec3(0.1f, 0.2f, 0.6f);
  base.clearcoat = 1.0f;
  base.clearcoatRoughness = 0.15f;
  c = renderBoth(gridUnderPointAndSphereLights(base), lookingAt({0, 0, 20}, 320, 160), o);
  EXPECT_LT(c.meanRelative, 1e-3);
  EXPECT_LT(c.fractionOver1, 5e-3);
}

namespace {

// A material extension in the viewer against the CPU: the quad of `quad` (its textures), seen
// up close, then the sphere grid of each of `bases` under a point light and a sphere light.
void expectExtensionMatches(const char* what, const QuadMaterial& quad,
                            const std::vector<Material>& bases) {
  TempDir dir;
  writeMaterialQuad(dir / "quad.gltf", quad);
  RenderOptions o;
  o.spp = 1;
  Comparison c =
      renderBoth(loadGltf((dir / "quad.gltf").string()), lookingAt({0.3f, 0.2f, 3.0f}, 64, 64), o);
  std::printf("%s quad: mean relative difference %.2e\n", what, c.meanRelative);
  EXPECT_LT(c.meanRelative, 1e-3);
  for (std::size_t k = 0; k < bases.size(); ++k) {
    c = renderBoth(gridUnderPointAndSphereLights(bases[k]), lookingAt({0, 0, 20}, 320, 160), o);
    std::printf("%s grid %zu: mean relative difference %.2e\n", what, k, c.meanRelative);
    EXPECT_LT(c.meanRelative, 1e-3) << what << " grid " << k;
    EXPECT_LT(c.fractionOver1, 5e-3) << what << " grid " << k;
  }
}

}  // namespace

// KHR_materials_iridescence: a quad whose film's strength and thickness come from a texture (R,
// G), and grids of iridescent spheres (a dielectric's film, then a metal's) under a point light
// and a sphere light (the film's Fresnel at n.v times the LTC's lobe).
TEST(Viewer, IridescenceMatchesTheCpu) {
  QuadMaterial m;
  m.baseColorFactor = glm::vec3(0.05f);
  m.metallicFactor = 0.0f;
  m.roughnessFactor = 0.3f;
  m.iridescenceFactor = 1.0f;
  m.iridescenceIor = 1.8f;
  m.iridescenceThicknessMinimum = 150.0f;
  m.iridescenceThicknessMaximum = 700.0f;
  m.iridescenceCodes = {220, 90, 0};
  std::vector<Material> bases;
  for (float metallic : {0.0f, 1.0f}) {
    Material base;
    base.baseColor = metallic > 0.0f ? glm::vec3(0.9f, 0.7f, 0.4f) : glm::vec3(0.02f);
    base.metallic = metallic;
    base.iridescence = 1.0f;
    base.iridescenceThicknessMaximum = 450.0f;
    bases.push_back(base);
  }
  expectExtensionMatches("iridescent", m, bases);
}

// KHR_materials_anisotropy: a quad whose direction and strength come from a texture (RG, B)
// turned by a rotation, and anisotropic grids (along the spheres' parallels, and turned 60
// degrees) under a point light and a sphere light: the bent reflection in the prefiltered map,
// anisotropic GGX at each light's representative point.
TEST(Viewer, AnisotropyMatchesTheCpu) {
  QuadMaterial m;
  m.baseColorFactor = glm::vec3(0.8f, 0.6f, 0.4f);
  m.metallicFactor = 1.0f;
  m.roughnessFactor = 0.3f;
  m.anisotropyStrength = 0.8f;
  m.anisotropyRotation = 0.7f;
  m.anisotropyCodes = {40, 200, 180};
  std::vector<Material> bases;
  for (float rotation : {0.0f, 1.05f}) {
    Material base;
    base.baseColor = glm::vec3(0.9f, 0.7f, 0.4f);
    base.anisotropy = 0.9f;
    base.anisotropyRotation = rotation;
    bases.push_back(base);
  }
  expectExtensionMatches("anisotropic", m, bases);
  // The quad without TEXCOORD_0: its texture off, as the CPU's lookups are (the direction along
  // the tangent turned by the rotation, not the texel at UV 0).
  TempDir dir;
  writeMaterialQuad(dir / "quad.gltf", m);
  nlohmann::json gltf = nlohmann::json::parse(std::ifstream(dir / "quad.gltf"));
  gltf["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
  std::ofstream(dir / "no_uvs.gltf") << gltf.dump();
  RenderOptions o;
  o.spp = 1;
  const Comparison c = renderBoth(loadGltf((dir / "no_uvs.gltf").string()),
                                  lookingAt({0.3f, 0.2f, 3.0f}, 64, 64), o);
  std::printf("anisotropic quad without UVs: mean relative difference %.2e\n", c.meanRelative);
  EXPECT_LT(c.meanRelative, 1e-3);
}

// KHR_materials_transmission and _volume: a quad whose transmission and thickness come from a
// texture (R, G) over an absorbing volume, and grids of transmissive spheres (thin walls, then
// solid and absorbing) under a point light and a sphere light: the light straight through,
// blurred by the transmission's roughness, the diffuse's share given up.
TEST(Viewer, TransmissionMatchesTheCpu) {
  QuadMaterial m;
  m.baseColorFactor = glm::vec3(0.8f, 0.9f, 0.6f);
  m.metallicFactor = 0.0f;
  m.roughnessFactor = 0.4f;
  m.transmissionFactor = 0.9f;
  m.thicknessFactor = 0.5f;
  m.attenuationDistance = 0.3f;
  m.attenuationColor = glm::vec3(0.9f, 0.5f, 0.2f);
  m.transmissionCodes = {200, 120, 0};
  std::vector<Material> bases;
  for (float thickness : {0.0f, 2.0f}) {
    Material base;
    base.baseColor = glm::vec3(0.9f, 0.8f, 0.6f);
    base.transmission = 1.0f;
    base.ior = 1.4f;
    base.thickness = thickness;
    base.attenuationDistance = 3.0f;
    base.attenuationColor = glm::vec3(0.4f, 0.7f, 0.9f);
    bases.push_back(base);
  }
  expectExtensionMatches("transmissive", m, bases);
}

// KHR_texture_transform on every slot the quad has: each reads a 4 x 4 bilinear texture through
// a transform of its own (offset, rotation, uneven scale), the normal maps included.
TEST(Viewer, TextureTransformsMatchTheCpu) {
  TempDir dir;
  QuadMaterial q;
  q.baseColorCodes = q.metallicRoughnessCodes = q.normalCodes = q.emissiveCodes = {255, 255, 255};
  q.metallicFactor = 0.5f;
  q.roughnessFactor = 0.8f;
  q.emissiveFactor = glm::vec3(0.2f);
  q.clearcoatFactor = 1.0f;
  q.clearcoatRoughnessFactor = 0.6f;
  q.clearcoatCodes = q.clearcoatNormalCodes = {255, 255, 255};
  writeMaterialQuad(dir / "quad.gltf", q);
  Scene scene = loadGltf((dir / "quad.gltf").string());
  scene.textures.push_back(gridTexture(230, false));
  Material& m = scene.materials.at(0);
  TextureRef* slots[] = {
      &m.baseColorTexture,         &m.metallicRoughnessTexture, &m.normalTexture,
      &m.emissiveTexture,          &m.clearcoatTexture,         &m.clearcoatNormalTexture,
      &m.clearcoatRoughnessTexture};
  for (int k = 0; k < 7; ++k) {
    slots[k]->index = static_cast<int>(scene.textures.size()) - 1;
    slots[k]->transform = {{0.1f * k, -0.2f}, 0.3f + 0.4f * k, {1.0f + 0.2f * k, 0.7f}};
  }
  RenderOptions o;
  o.spp = 1;
  const Comparison c = renderBoth(scene, lookingAt({0.3f, 0.2f, 3.0f}, 64, 64), o);
  std::printf("texture transforms: mean relative difference %.5f\n", c.meanRelative);
  // Without the transforms the same textures differ by 0.2 % too: the device's bilinear weights
  // have 8 bits, and the normal maps' steep texels turn that into shading. Dropping the
  // viewer's transforms makes it 91 %.
  EXPECT_LT(c.meanRelative, 4e-3);
  EXPECT_LT(c.coverageMismatch, 5e-3);
}

// COLOR_0 multiplies the base color and its alpha: a quad whose vertices' colors differ in every
// channel (the colors interpolated across it), masked where the vertices' alpha falls below the
// cutoff, lit by the environment and a point light; then unlit, where they multiply the color
// it shows.
TEST(Viewer, VertexColorsMatchTheCpu) {
  for (bool unlit : {false, true}) {
    TempDir dir;
    QuadMaterial q;
    q.baseColorCodes = {255, 200, 160};
    q.metallicFactor = 0.0f;
    q.roughnessFactor = 0.5f;
    q.alphaMode = "MASK";
    q.unlit = unlit;
    writeMaterialQuad(dir / "quad.gltf", q);
    Scene scene = loadGltf((dir / "quad.gltf").string());
    Mesh& mesh = scene.meshes.at(0);
    const glm::vec4 corners[4] = {{1.0f, 0.1f, 0.2f, 1.0f},
                                  {0.1f, 1.0f, 0.3f, 0.8f},
                                  {0.2f, 0.3f, 1.0f, 0.1f},
                                  {0.9f, 0.9f, 0.1f, 0.6f}};
    mesh.colors.clear();
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) mesh.colors.push_back(corners[i % 4]);
    scene.lights.push_back(
        viewerTestLight(LightType::Point, {1.0f, 1.0f, 2.0f}, {0.0f, 0.0f, -1.0f}, 30.0f, 1.0f));
    RenderOptions o;
    o.spp = 1;
    const Comparison c = renderBoth(scene, lookingAt({0.3f, 0.2f, 3.0f}, 64, 64), o);
    std::printf("vertex colors%s: mean relative difference %.2e, coverage mismatch %.4f\n",
                q.unlit ? " (unlit)" : "", c.meanRelative, c.coverageMismatch);
    EXPECT_LT(c.meanRelative, 1e-3);
    EXPECT_LT(c.coverageMismatch, 5e-3);
  }
}

// A transform's screen derivatives: a floor seen at a glance minifies a checker texture (mip
// levels, read at the derivatives of the transformed UVs) through a transform that scales it 6 x
// 4 and turns it, and is drawn again with the same map applied to its vertices' UVs instead (the
// map is affine: the same UVs). The two frames agree; derivatives left untransformed would pick
// other mip levels.
TEST(Viewer, TextureTransformEqualsTheSameMapInTheUvs) {
  Texture checker;
  checker.width = checker.height = 64;
  auto rgba = std::make_shared<std::vector<std::uint8_t>>();
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool dark = ((x / 4) + (y / 4)) % 2 == 0;
      rgba->insert(rgba->end(), {static_cast<std::uint8_t>(dark ? 20 : 240),
                                 static_cast<std::uint8_t>(dark ? 60 : 200), 120, 255});
    }
  checker.rgba = rgba;
  Material m;
  m.metallic = 0.0f;
  m.baseColorTexture.index = 0;
  m.baseColorTexture.transform = {{0.2f, 0.1f}, 0.3f, {6.0f, 4.0f}};
  Mesh floor;
  floor.positions = {{-4, -1, -4}, {4, -1, -4}, {4, -1, 4}, {-4, -1, 4}};
  floor.normals.assign(4, glm::vec3(0, 1, 0));
  floor.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  floor.indices = {0, 2, 1, 0, 3, 2};
  Scene transformed;
  transformed.textures = {checker};
  transformed.materials = {m};
  transformed.meshes = {floor};
  Scene baked = transformed;
  const TextureTransform& t = m.baseColorTexture.transform;
  for (glm::vec2& uv : baked.meshes[0].uvs)
    uv = shared::transformUv(shared::uvTransformOf(t.offset, t.rotation, t.scale), uv);
  baked.materials[0].baseColorTexture.transform = TextureTransform{};
  Camera camera = lookingAt({0.0f, 0.2f, 4.5f}, 96, 64);
  camera.at = glm::vec3(0.0f, -1.0f, 0.0f);
  RenderOptions o;
  o.spp = 1;
  gpu::SceneRenderer a(graphicsContext(), transformed, sunsetBake().bake, sunsetBake().options);
  gpu::SceneRenderer b(graphicsContext(), baked, sunsetBake().bake, sunsetBake().options);
  const Comparison c = compare(a.render(camera, o), b.render(camera, o));
  std::printf("transform against the same map in the UVs: mean relative difference %.6f\n",
              c.meanRelative);
  EXPECT_LT(c.meanRelative, 1e-4);
  EXPECT_EQ(c.coverageMismatch, 0.0);
}

TEST(Viewer, TexturedAndCompressedMeshesMatchTheCpu) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf");
  RenderOptions o;
  o.spp = 1;
  Comparison c =
      renderBoth(loadGltf((dir / "quad.gltf").string()), lookingAt({0.3f, 0.2f, 3.0f}, 96, 96), o);
  EXPECT_LT(c.meanRelative, 1e-3);
  EXPECT_LT(c.coverageMismatch, 5e-3);
  // A MASK material cuts the same holes (a texture whose left half is under the cutoff).
  QuadMaterial masked;
  masked.alphaCodes = {77, 204};
  masked.alphaMode = "MASK";
  writeMaterialQuad(dir / "mask.gltf", masked);
  c = renderBoth(loadGltf((dir / "mask.gltf").string()), lookingAt({0.3f, 0.2f, 3.0f}, 96, 96), o);
  EXPECT_LT(c.meanRelative, 1e-3);
  EXPECT_LT(c.coverageMismatch, 5e-3);
  // The second UV set, a clamping nearest sampler, an sRGB texture format with mip maps.
  writeTexturedQuad(dir / "quad1.gltf", true);
  c = renderBoth(loadGltf((dir / "quad1.gltf").string()), lookingAt({0.3f, 0.2f, 3.0f}, 96, 96), o);
  EXPECT_LT(c.meanRelative, 1e-3);
  EXPECT_LT(c.coverageMismatch, 5e-3);
  const Scene bunny = loadGltf((dataDir() / "models" / "bunny.glb").string());
  const auto [lo, hi] = bunny.bounds();
  Camera camera =
      lookingAt(0.5f * (lo + hi) + glm::vec3(0, 0, 2.5f * glm::length(hi - lo)), 128, 128);
  camera.at = 0.5f * (lo + hi);
  c = renderBoth(bunny, camera, o);
  EXPECT_LT(c.meanRelative, 2e-3);
  EXPECT_LT(c.fractionOver1, 2e-2);
  EXPECT_LT(c.coverageMismatch, 1e-2);
}
