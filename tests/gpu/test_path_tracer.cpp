// The GPU reference (ibl/gpu/path_tracer.hpp) against the CPU's (renderScene in
// RenderMode::Reference) on the scenes issue 34 names: the built-in sphere grid (the microfacet
// walk, four bounces), glTF-style textured meshes with MASK and BLEND alpha and a textured
// emitter, every light type, and a room lit through a window. Two checks per scene:
//  - independent seeds: the difference of two independent estimates has the sum of their
//    variances, so z = (gpu - cpu) / sqrt(2 var / spp), var the GPU's per-pixel variance of one
//    sample's luminance, rarely exceeds 5; and the mean luminances agree within 0.5 % (or the
//    difference's own standard error);
//  - the same seed: both draw the same numbers (ibl/shared/path_sampler.h), so most pixels agree
//    to float rounding, which a path that takes another branch on either side cannot.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "ibl/gpu/compute.hpp"
#include "ibl/gpu/path_tracer.hpp"
#include "ibl/io/ies.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/renderer.hpp"
#include "support/gltf_writer.hpp"
#include "support/light_scenes.hpp"
#include "support/room.hpp"
#include "support/sphere_renders.hpp"

namespace ibl {
namespace {

gpu::Context* device() {
  static const std::unique_ptr<gpu::Context> c = [] {
    try {
      return gpu::Context::create();
    } catch (const Error&) {
      return std::unique_ptr<gpu::Context>();
    }
  }();
  return c.get();
}

// An environment with a sky gradient and a small bright sun, baked small.
const test::Baked& skyBake() {
  static const test::Baked b = test::bakeOf(
      [](glm::vec3 d) {
        const glm::vec3 sun = glm::normalize(glm::vec3(0.4f, 0.8f, 0.45f));
        const float s = std::pow(std::max(glm::dot(d, sun), 0.0f), 60.0f);
        return glm::vec3(0.6f, 0.7f, 1.0f) * (1.0f + 0.5f * d.y) + glm::vec3(20.0f) * s;
      },
      32);
  return b;
}

struct Agreement {
  double meanRatio = 0.0;       // mean luminance, GPU / CPU
  double ratioError = 0.0;      // the standard error of meanRatio, from the pixels' variances
  double outliers = 0.0;        // the share of pixels whose |z| exceeds 5
  double sameSeedMedian = 0.0;  // median |gpu - cpu| / cpu over the lit pixels, same seed
  std::size_t pixels = 0;
};

Agreement compare(const Scene& scene, const Camera& camera, const BakeResult& bake,
                  const BakeOptions& bakeOptions, RenderOptions o, int spp) {
  o.mode = RenderMode::Reference;
  o.spp = spp;
  o.seed = 1;
  const RenderResult cpu = renderScene(scene, camera, bake, bakeOptions, o);
  gpu::PathTracer tracer(*device(), scene, bake, bakeOptions);
  Agreement a;
  std::vector<double> sameSeed;
  double cpuMean = 0.0;
  for (const glm::vec3& c : cpu.color.pixels) cpuMean += luminance(c);
  cpuMean /= static_cast<double>(cpu.color.pixels.size());
  {
    tracer.reset(camera, o);
    tracer.accumulate(spp);
    const RenderResult same = tracer.result();
    // Over the pixels that show something lit: the background and unlit pixels agree anyway.
    for (std::size_t i = 0; i < same.color.pixels.size(); ++i) {
      const double c = luminance(cpu.color.pixels[i]), g = luminance(same.color.pixels[i]);
      if (cpu.alpha[i] > 0.0f && c > 1e-3 * cpuMean) sameSeed.push_back(std::abs(g - c) / c);
    }
  }
  EXPECT_GT(sameSeed.size(), 100u);
  if (sameSeed.empty()) return a;
  const auto middle = sameSeed.begin() + static_cast<std::ptrdiff_t>(sameSeed.size() / 2);
  std::nth_element(sameSeed.begin(), middle, sameSeed.end());
  a.sameSeedMedian = *middle;
  o.seed = 2;
  tracer.reset(camera, o);
  // Two batches: the accumulation goes on across dispatches.
  tracer.accumulate(spp / 2);
  tracer.accumulate(spp - spp / 2);
  EXPECT_EQ(tracer.samplesPerPixel(), spp);
  const RenderResult g = tracer.result();
  const std::vector<float> variance = tracer.luminanceVariance();
  double cpuSum = 0.0, gpuSum = 0.0, varianceOfSum = 0.0;
  std::size_t outliers = 0, coverageMismatches = 0;
  for (std::size_t i = 0; i < g.color.pixels.size(); ++i) {
    const double c = luminance(cpu.color.pixels[i]), l = luminance(g.color.pixels[i]);
    cpuSum += c;
    gpuSum += l;
    if (std::abs(g.alpha[i] - cpu.alpha[i]) > 0.35f) ++coverageMismatches;
    varianceOfSum += 2.0 * variance[i] / spp;
    if (!(variance[i] > 0.0f)) continue;
    // A floor of 0.2 % for pixels nearly without noise (a punctual light's direct light): float
    // rounding is not noise.
    const double z2 = (l - c) * (l - c) / (2.0 * variance[i] / spp + (2e-3 * c) * (2e-3 * c));
    if (z2 > 25.0) ++outliers;
    ++a.pixels;
  }
  const double count = static_cast<double>(g.color.pixels.size());
  a.meanRatio = gpuSum / cpuSum;
  a.ratioError = std::sqrt(varianceOfSum) / cpuSum;
  // Edges: the two seeds' samples fall on either side of a silhouette.
  EXPECT_LT(static_cast<double>(coverageMismatches) / count, 0.02);
  a.outliers =
      static_cast<double>(outliers) / static_cast<double>(std::max<std::size_t>(a.pixels, 1));
  return a;
}

// The means agree within 0.5 % or, where the image's own noise is larger (a small sun through
// a window), within 4 standard errors of the difference; few pixels stray beyond 5 sigma (the
// per-pixel variance of 64 low-discrepancy samples overstates their error and misses rare
// paths, so the pixels' z^2 do not average 1 exactly); the same seed gives the same image.
void expectAgreement(const Agreement& a) {
  EXPECT_LT(std::abs(a.meanRatio - 1.0), std::max(0.005, 4.0 * a.ratioError))
      << "standard error " << a.ratioError;
  EXPECT_GT(a.pixels, 100u);
  EXPECT_LT(a.outliers, 0.04);
  EXPECT_LT(a.sameSeedMedian, 1e-3);
}

// The sphere grid from +Z, 48 x 24 pixels.
Camera gridCamera() {
  Camera camera;
  camera.from = glm::vec3(0.0f, 0.0f, 14.0f);
  camera.at = glm::vec3(0.0f);
  camera.yfovDegrees = 30.0f;
  camera.width = 48;
  camera.height = 24;
  return camera;
}

// The scene from gridCamera with one bounce, 64 samples per pixel: the GPU and the CPU agree
// (expectAgreement); `what` names the scene in the printed figures.
void expectOneBounceAgreement(const Scene& scene, const char* what) {
  RenderOptions o;
  o.bounces = 1;
  const Agreement a = compare(scene, gridCamera(), skyBake().result, skyBake().options, o, 64);
  std::printf("%s: GPU / CPU mean %.4f, outliers %.4f, same seed median %.2e\n", what, a.meanRatio,
              a.outliers, a.sameSeedMedian);
  expectAgreement(a);
}

#define REQUIRE_DEVICE() \
  if (!device()) GTEST_SKIP() << "no Vulkan device"

TEST(GpuReference, SphereGridWithTheWalkEqualsTheCpu) {
  REQUIRE_DEVICE();
  const Scene scene = makeSphereGrid(glm::vec3(0.9f, 0.6f, 0.3f));
  const Camera camera = gridCamera();
  RenderOptions o;
  o.multipleScattering = MultipleScattering::Walk;
  o.bounces = 4;
  const Agreement a = compare(scene, camera, skyBake().result, skyBake().options, o, 64);
  expectAgreement(a);
}

// A wall of material `material` behind the sphere grid (z = -2, 18 x 10), its texture repeated
// 6 x 4 times.
Mesh textureWall(int material) {
  Mesh wall;
  wall.positions = {{-9, -5, -2}, {9, -5, -2}, {9, 5, -2}, {-9, 5, -2}};
  wall.normals.assign(4, glm::vec3(0, 0, 1));
  wall.uvs = {{0, 0}, {6, 0}, {6, 4}, {0, 4}};
  wall.indices = {0, 1, 2, 0, 2, 3};
  wall.material = material;
  return wall;
}

// Black dielectrics whose specular layer (KHR_materials_ior 2.4, KHR_materials_specular 0.6 of
// a green-heavy color) is all they reflect: luminance follows the layer's color. Behind them a
// black backdrop takes its layer from textures: color from RGB (sRGB), strength from A, each
// texel different in both.
TEST(GpuReference, IorAndSpecularLayersEqualTheCpu) {
  REQUIRE_DEVICE();
  Material base;
  base.baseColor = glm::vec3(0.0f);
  base.ior = 2.4f;
  base.specular = 0.6f;
  base.specularColor = glm::vec3(0.1f, 3.0f, 0.5f);
  Scene scene = makeSphereGrid(base);
  Texture layer;
  layer.width = layer.height = 2;
  layer.rgba = std::make_shared<std::vector<std::uint8_t>>(std::vector<std::uint8_t>{
      255, 255, 255, 40, 255, 128, 30, 255, 60, 255, 60, 128, 255, 255, 255, 255});
  layer.sampler.nearest = true;
  scene.textures = {layer};
  Material backdrop = base;
  backdrop.metallic = 0.0f;
  backdrop.roughness = 0.3f;
  backdrop.specularColor = glm::vec3(8.0f);
  backdrop.specularColorTexture.index = 0;
  backdrop.specularTexture.index = 0;
  scene.materials.push_back(backdrop);
  scene.meshes.push_back(textureWall(static_cast<int>(scene.materials.size()) - 1));
  expectOneBounceAgreement(scene, "ior and specular layers");
}

// KHR_materials_clearcoat: a coated grid, and a wall whose coat's strength and roughness come
// from a texture (R, G) and whose coat has a normal map of its own.
TEST(GpuReference, ClearcoatEqualsTheCpu) {
  REQUIRE_DEVICE();
  Material base;
  base.baseColor = glm::vec3(0.6f, 0.1f, 0.1f);
  base.clearcoat = 1.0f;
  base.clearcoatRoughness = 0.1f;
  Scene scene = makeSphereGrid(base);
  Texture coat, bumps;
  coat.width = coat.height = bumps.width = bumps.height = 2;
  coat.rgba = std::make_shared<std::vector<std::uint8_t>>(std::vector<std::uint8_t>{
      255, 20, 0, 255, 128, 128, 0, 255, 40, 255, 0, 255, 255, 200, 0, 255});
  bumps.rgba = std::make_shared<std::vector<std::uint8_t>>(std::vector<std::uint8_t>{
      200, 128, 230, 255, 60, 128, 230, 255, 128, 200, 230, 255, 128, 60, 230, 255});
  coat.sampler.nearest = bumps.sampler.nearest = true;
  scene.textures = {coat, bumps};
  Material backdrop = base;
  backdrop.baseColor = glm::vec3(0.05f);
  backdrop.metallic = 0.0f;
  backdrop.roughness = 0.6f;
  backdrop.clearcoatRoughness = 0.8f;
  backdrop.clearcoatTexture.index = 0;
  backdrop.clearcoatRoughnessTexture.index = 0;
  backdrop.clearcoatNormalTexture.index = 1;
  scene.materials.push_back(backdrop);
  Mesh wall = textureWall(static_cast<int>(scene.materials.size()) - 1);
  wall.tangents.assign(4, glm::vec4(1, 0, 0, 1));
  scene.meshes.push_back(wall);
  expectOneBounceAgreement(scene, "clear coat");
  // The wall alone fills the frame: its coat's textures and normal map decide every pixel.
  Scene wallOnly;
  wallOnly.textures = scene.textures;
  wallOnly.materials = {backdrop};
  wall.material = 0;
  wallOnly.meshes = {wall};
  expectOneBounceAgreement(wallOnly, "clear coat's textures");
}

namespace {

// A 2 x 2 texture of `rgba` (four RGBA texels), sampled nearest.
Texture nearestTexture(std::vector<std::uint8_t> rgba) {
  Texture t;
  t.width = t.height = 2;
  t.rgba = std::make_shared<std::vector<std::uint8_t>>(std::move(rgba));
  t.sampler.nearest = true;
  return t;
}

// The sphere grid of `base` before a textureWall of material `wall` (which reads `texture`; its
// tangents along +X), lit by the sky and a point light above.
Scene gridBeforeTexturedWall(const Material& base, const Texture& texture, const Material& wall) {
  Scene scene = makeSphereGrid(base);
  scene.textures = {texture};
  scene.materials.push_back(wall);
  Mesh w = textureWall(static_cast<int>(scene.materials.size()) - 1);
  w.tangents.assign(4, glm::vec4(1, 0, 0, 1));
  scene.meshes.push_back(w);
  Light point;
  point.type = LightType::Point;
  point.position = glm::vec3(0.0f, 8.0f, -4.0f);
  point.intensity = 400.0f;
  scene.lights.push_back(point);
  return scene;
}

// A thin wall of roughness r that transmits (orange), its share from texture 0
// (transmissionShares).
Material transmissiveWall(float r) {
  Material wall;
  wall.baseColor = glm::vec3(0.8f, 0.5f, 0.3f);
  wall.metallic = 0.0f;
  wall.roughness = r;
  wall.transmission = 1.0f;
  wall.transmissionTexture.index = 0;
  return wall;
}

// A 2 x 2 texture of transmission shares in R: 1, 0.24, 0, 0.71.
Texture transmissionShares() {
  return nearestTexture({255, 0, 0, 255, 60, 0, 0, 255, 0, 0, 0, 255, 180, 0, 0, 255});
}

}  // namespace

// KHR_materials_iridescence: a grid of metals under a film (the walk's bounces each take the film's
// Fresnel), and a wall whose film's strength and thickness come from a texture (R, G), lit by the
// sky and a point light.
TEST(GpuReference, IridescenceEqualsTheCpu) {
  REQUIRE_DEVICE();
  Material base;
  base.baseColor = glm::vec3(0.9f, 0.6f, 0.3f);
  base.iridescence = 1.0f;
  base.iridescenceIor = 1.5f;
  base.iridescenceThicknessMaximum = 500.0f;
  Material wall;
  wall.baseColor = glm::vec3(0.02f);
  wall.metallic = 0.0f;
  wall.roughness = 0.3f;
  wall.iridescence = 1.0f;
  wall.iridescenceIor = 2.0f;
  wall.iridescenceThicknessMinimum = 100.0f;
  wall.iridescenceThicknessMaximum = 800.0f;
  wall.iridescenceTexture.index = 0;
  wall.iridescenceThicknessTexture.index = 0;
  const Texture film =
      nearestTexture({255, 20, 0, 255, 128, 128, 0, 255, 40, 255, 0, 255, 255, 200, 0, 255});
  expectOneBounceAgreement(gridBeforeTexturedWall(base, film, wall), "iridescence");
}

// KHR_materials_anisotropy: a grid of anisotropic spheres (the walk's bounces in the lobe's
// frame), and a wall whose direction and strength come from a texture (RG, B) turned by a
// rotation, lit by the sky and a point light.
TEST(GpuReference, AnisotropyEqualsTheCpu) {
  REQUIRE_DEVICE();
  Material base;
  base.baseColor = glm::vec3(0.9f, 0.6f, 0.3f);
  base.anisotropy = 0.8f;
  base.anisotropyRotation = 0.4f;
  Material wall;
  wall.baseColor = glm::vec3(0.7f);
  wall.metallic = 1.0f;
  wall.roughness = 0.2f;
  wall.anisotropy = 1.0f;
  wall.anisotropyRotation = -0.5f;
  wall.anisotropyTexture.index = 0;
  const Texture brushed =
      nearestTexture({255, 128, 255, 255, 128, 255, 200, 255, 30, 60, 255, 255, 220, 40, 90, 255});
  expectOneBounceAgreement(gridBeforeTexturedWall(base, brushed, wall), "anisotropy");
}

// KHR_materials_transmission and _volume: a grid of solid glass spheres (refracted in and out,
// absorbed inside; the metals above them transmit nothing) before a thin transmissive wall whose
// share comes from a texture (R), lit by the sky and a point light; four bounces carry the light
// through a sphere.
TEST(GpuReference, TransmissionEqualsTheCpu) {
  REQUIRE_DEVICE();
  Material base;
  base.baseColor = glm::vec3(0.9f, 0.95f, 1.0f);
  base.transmission = 1.0f;
  base.thickness = 2.0f;
  base.attenuationDistance = 1.5f;
  base.attenuationColor = glm::vec3(0.9f, 0.6f, 0.3f);
  const Material wall = transmissiveWall(0.3f);
  const Texture share = transmissionShares();
  RenderOptions o;
  o.bounces = 4;
  // Seen by the camera, and as a probe captures it (the diffuse and the transmission of the
  // surfaces in view and of those seen through them: path_brdf.h's kLobesCapture).
  for (const bool capture : {false, true}) {
    o.cameraSeesSpecular = !capture;
    const Agreement a = compare(gridBeforeTexturedWall(base, share, wall), gridCamera(),
                                skyBake().result, skyBake().options, o, 64);
    std::printf("transmission%s: GPU / CPU mean %.4f, outliers %.4f, same seed median %.2e\n",
                capture ? " (capture)" : "", a.meanRatio, a.outliers, a.sameSeedMedian);
    expectAgreement(a);
  }
}

// Smooth thin walls, which the path crosses straight and the shadow rays pass
// (pathCrossesStraight in ibl/shared/path_brdf.h): the grid lit through the smooth wall behind it
// (its share from a texture, 0 in one texel) by the point light and the sky beyond, and seen
// through a smooth tinted pane over the left half of the view.
TEST(GpuReference, SmoothThinWallsPassLightAsOnTheCpu) {
  REQUIRE_DEVICE();
  Material base;
  base.baseColor = glm::vec3(0.8f, 0.7f, 0.6f);
  const Material wall = transmissiveWall(0.0f);
  const Texture share = transmissionShares();
  Scene scene = gridBeforeTexturedWall(base, share, wall);
  Material pane = wall;
  pane.baseColor = glm::vec3(0.9f, 0.8f, 0.6f);
  pane.transmissionTexture.index = -1;
  scene.materials.push_back(pane);
  Mesh glass = textureWall(static_cast<int>(scene.materials.size()) - 1);
  for (glm::vec3& q : glass.positions) q = glm::vec3(std::min(q.x, 0.0f), q.y, 6.0f);
  scene.meshes.push_back(glass);
  RenderOptions o;
  o.bounces = 2;
  const Agreement a = compare(scene, gridCamera(), skyBake().result, skyBake().options, o, 64);
  std::printf("smooth thin walls: GPU / CPU mean %.4f, outliers %.4f, same seed median %.2e\n",
              a.meanRatio, a.outliers, a.sameSeedMedian);
  expectAgreement(a);
}

// KHR_materials_sheen at a sheen roughness of 0.15, where the Charlie Lambda is the tabulated
// exact one over most angles (shared::charlieLambda): the device reads the table from its buffer,
// the CPU from the header's array. A point light adds the lobe's direct light.
TEST(GpuReference, SheenEqualsTheCpu) {
  REQUIRE_DEVICE();
  Material base;
  base.baseColor = glm::vec3(0.1f, 0.15f, 0.4f);
  base.sheenColor = glm::vec3(1.0f, 0.8f, 0.6f);
  base.sheenRoughness = 0.15f;
  Scene scene = makeSphereGrid(base);
  Light point;
  point.type = LightType::Point;
  point.position = glm::vec3(0.0f, 8.0f, -4.0f);
  point.intensity = 400.0f;
  scene.lights.push_back(point);
  expectOneBounceAgreement(scene, "sheen");
}

// COLOR_0: a wall whose four corners' colors differ in every channel, masked where the
// interpolated alpha falls below the cutoff (the rays' coverage test reads it too). Its right
// half is unlit, as the loader converts KHR_materials_unlit: there the colors multiply the
// emission that shows the base color.
TEST(GpuReference, VertexColorsEqualTheCpu) {
  REQUIRE_DEVICE();
  Material m;
  m.baseColor = glm::vec3(0.9f, 0.8f, 0.7f);
  m.roughness = 0.4f;
  m.alphaMode = AlphaMode::Mask;
  Material unlit = m;
  unlit.unlit = true;
  unlit.emissive = m.baseColor;
  unlit.baseColor = glm::vec3(0.0f);
  unlit.specular = 0.0f;
  Scene scene;
  scene.materials = {m, unlit};
  for (int half = 0; half < 2; ++half) {
    Mesh wall = textureWall(half);
    for (int k : {0, 3}) wall.positions[static_cast<std::size_t>(k)].x = half == 0 ? -9.0f : 0.0f;
    for (int k : {1, 2}) wall.positions[static_cast<std::size_t>(k)].x = half == 0 ? 0.0f : 9.0f;
    wall.colors = {{1.0f, 0.1f, 0.2f, 1.0f},
                   {0.1f, 1.0f, 0.3f, 0.8f},
                   {0.2f, 0.3f, 1.0f, 0.1f},
                   {0.9f, 0.9f, 0.1f, 0.6f}};
    scene.meshes.push_back(wall);
  }
  expectOneBounceAgreement(scene, "vertex colors, lit and unlit");
}

// KHR_texture_transform: a wall whose base color and emission read a 4 x 4 texture through
// transforms of their own (offset, rotation, uneven scale).
TEST(GpuReference, TextureTransformsEqualTheCpu) {
  REQUIRE_DEVICE();
  Material wall;
  wall.baseColor = glm::vec3(0.9f);
  wall.metallic = 0.0f;
  wall.roughness = 0.7f;
  wall.baseColorTexture.index = 0;
  wall.baseColorTexture.transform = {{0.3f, -0.2f}, 0.5f, {1.7f, 0.8f}};
  wall.emissive = glm::vec3(0.5f);
  wall.emissiveTexture.index = 0;
  wall.emissiveTexture.transform = {{0.1f, 0.4f}, -1.1f, {0.6f, 1.3f}};
  Scene scene;
  scene.textures = {test::gridTexture(150, true)};
  scene.materials = {wall};
  scene.meshes = {textureWall(0)};
  expectOneBounceAgreement(scene, "texture transforms");
}

// Textures with each wrap mode, MASK and BLEND alpha from a texture's A, a normal map's
// absence handled, and a textured emitter sampled as a light.
Scene texturedScene() {
  Scene s;
  Texture checker;
  checker.width = checker.height = 8;
  auto rgba = std::make_shared<std::vector<std::uint8_t>>();
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool on = (x + y) % 2 == 0;
      rgba->insert(
          rgba->end(),
          {static_cast<std::uint8_t>(on ? 230 : 40), static_cast<std::uint8_t>(40 + 25 * x),
           static_cast<std::uint8_t>(40 + 25 * y), static_cast<std::uint8_t>(on ? 255 : 60)});
    }
  checker.rgba = rgba;
  checker.sampler.wrapS = Wrap::MirroredRepeat;
  s.textures = {checker, checker};
  s.textures[1].sampler.wrapS = Wrap::ClampToEdge;
  s.textures[1].sampler.nearest = true;
  Material floor;
  floor.metallic = 0.0f;
  floor.roughness = 0.3f;
  floor.baseColorTexture.index = 0;
  Material mask = floor;
  mask.alphaMode = AlphaMode::Mask;
  mask.baseColorTexture.index = 1;
  mask.metallic = 1.0f;
  mask.roughness = 0.3f;
  Material blend = floor;
  blend.alphaMode = AlphaMode::Blend;
  Material lamp;
  lamp.baseColor = glm::vec3(0.0f);
  lamp.emissive = glm::vec3(8.0f);
  lamp.emissiveTexture.index = 0;
  // A black glossy dielectric whose specular layer comes from textures (KHR_materials_specular:
  // color from RGB, sRGB; strength from A), over an IOR of 1.8.
  Material glossy;
  glossy.baseColor = glm::vec3(0.0f);
  glossy.metallic = 0.0f;
  glossy.roughness = 0.25f;
  glossy.ior = 1.8f;
  glossy.specularColor = glm::vec3(5.0f);
  glossy.specularColorTexture.index = 0;
  glossy.specularTexture.index = 1;
  s.materials = {floor, mask, blend, lamp, glossy};
  const auto quad = [&](glm::vec3 corner, glm::vec3 u, glm::vec3 v, int material) {
    Mesh m;
    m.positions = {corner, corner + u, corner + u + v, corner + v};
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    m.normals.assign(4, n);
    m.uvs = {{-0.5f, -0.5f}, {1.5f, -0.5f}, {1.5f, 1.5f}, {-0.5f, 1.5f}};
    m.indices = {0, 1, 2, 0, 2, 3};
    m.material = material;
    s.meshes.push_back(m);
  };
  quad({-2, 0, -2}, {0, 0, 4}, {4, 0, 0}, 0);
  quad({-1.2f, 0.2f, -1}, {0, 1.2f, 0}, {1, 0, 0.3f}, 1);
  quad({0.3f, 0.1f, -0.5f}, {0, 1.0f, 0.2f}, {1, 0, 0}, 2);
  quad({-1.0f, 1.2f, -1.0f}, {2, 0, 0}, {0, 0, 2}, 3);
  quad({0.8f, 0.0f, 0.6f}, {0, 0.8f, 0}, {0.8f, 0, -0.3f}, 4);
  return s;
}

TEST(GpuReference, TexturedAlphaAndEmissiveMeshesEqualTheCpu) {
  REQUIRE_DEVICE();
  const Scene scene = texturedScene();
  Camera camera;
  camera.from = glm::vec3(2.5f, 2.0f, 3.0f);
  camera.at = glm::vec3(0.0f, 0.5f, 0.0f);
  camera.width = 40;
  camera.height = 30;
  RenderOptions o;
  o.bounces = 2;
  const Agreement a = compare(scene, camera, skyBake().result, skyBake().options, o, 64);
  expectAgreement(a);
}

TEST(GpuReference, EveryLightTypeEqualsTheCpu) {
  REQUIRE_DEVICE();
  Material material;
  material.baseColor = glm::vec3(0.7f);
  material.metallic = 0.0f;
  material.roughness = 0.4f;
  const test::BlackBake black = test::blackBake();
  for (LightType type : {LightType::Point, LightType::Spot, LightType::Sun, LightType::Sphere,
                         LightType::Disk, LightType::Rect, LightType::Tube}) {
    SCOPED_TRACE(static_cast<int>(type));
    Scene scene = test::studyScene(test::StudyShape::Plane, test::studyLight(type), material);
    scene.spheres.push_back({glm::vec3(0.4f, 0.35f, -0.2f), 0.3f, 0});
    const Camera camera = [] {
      Camera c = test::studyCamera(test::StudyShape::Plane, 32);
      c.height = 24;
      return c;
    }();
    RenderOptions o;
    o.bounces = 1;
    o.environmentLight = false;
    expectAgreement(compare(scene, camera, black.result, black.options, o, 64));
  }
}

// IES profiles: the device reads each light's intensity from a table of 0.5-degree steps
// (bilinear), the CPU the profile's bicubic interpolation; an asymmetric profile, so that a
// horizontal angle read the wrong way round shows.
TEST(GpuReference, IesLightsEqualTheCpu) {
  REQUIRE_DEVICE();
  const auto profile =
      std::make_shared<const IesProfile>(parseIes(test::asymmetricIesText(), "test.ies"));
  Material material;
  material.baseColor = glm::vec3(0.7f);
  material.metallic = 0.0f;
  material.roughness = 0.4f;
  const test::BlackBake black = test::blackBake();
  for (LightType type : {LightType::Point, LightType::Spot}) {
    SCOPED_TRACE(static_cast<int>(type));
    Light light = test::studyLight(type);
    light.ies = profile;
    light.outerAngle = std::max(light.outerAngle, 1.2f);
    Scene scene = test::studyScene(test::StudyShape::Plane, light, material);
    Camera camera = test::studyCamera(test::StudyShape::Plane, 32);
    camera.height = 24;
    RenderOptions o;
    o.bounces = 1;
    o.environmentLight = false;
    // The table's bilinear interpolation against the profile's bicubic one: within the same
    // seed's 0.1 %.
    expectAgreement(compare(scene, camera, black.result, black.options, o, 64));
  }
}

TEST(GpuReference, RoomThroughAWindowEqualsTheCpu) {
  REQUIRE_DEVICE();
  test::RoomDescription room;
  for (auto& wall : room.walls) {
    wall[0].baseColor = glm::vec3(0.8f, 0.7f, 0.6f);
    wall[0].metallic = 0.0f;
    wall[1].baseColor = glm::vec3(0.3f, 0.5f, 0.7f);
    wall[1].metallic = 0.0f;
    wall[1].roughness = 0.3f;
  }
  room.window = true;
  Scene scene = test::makeRoom(room);
  scene.spheres.push_back({glm::vec3(0.0f, 0.6f, 0.0f), 0.6f, 0});
  Camera camera;
  camera.from = glm::vec3(-1.8f, 1.6f, 1.8f);
  camera.at = glm::vec3(1.0f, 1.0f, -0.5f);
  camera.yfovDegrees = 70.0f;
  camera.width = 40;
  camera.height = 30;
  RenderOptions o;
  o.bounces = 4;
  o.backgroundEnvironment = false;
  const Agreement a = compare(scene, camera, skyBake().result, skyBake().options, o, 64);
  expectAgreement(a);
}

}  // namespace
}  // namespace ibl
