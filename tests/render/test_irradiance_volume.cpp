// The irradiance volume (src/render/irradiance_volume.cpp): captures against closed forms (a
// constant and a half-sphere sky, distances inside a sphere), relocation out of a solid box,
// the CPU lookup on its atlases (a constant and a linear field, a floor between two layers of
// probes), the files' round trip and errors, and the split sum's composition rule.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/render/irradiance_volume.hpp"
#include "ibl/render/renderer.hpp"
#include "support/helpers.hpp"
#include "support/room.hpp"
#include "support/small_bake.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

struct VolumeBake {
  BakeOptions options;
  BakeResult result;
};

VolumeBake bakeOfSky(const RadianceFn& sky) {
  VolumeBake b;
  b.options.specular.size = 32;
  b.options.irradianceSize = 8;
  b.options.dfgSize = 16;
  b.options.dfgSamples = 64;
  b.result = bakeEnvironment(equirectEnvironment(equirectFromFunction(256, sky)), b.options);
  return b;
}

// The top-left texel of probe `index`'s tile, as docs/probes.md lays the atlas out.
glm::ivec2 tileCorner(const VolumeGrid& g, int index, int texels) {
  const int perRow = g.counts.x * g.counts.y;
  return glm::ivec2(index % perRow, index / perRow) * (texels + 2);
}

void fillTile(Image& atlas, const VolumeGrid& g, int index, int texels, glm::vec3 value) {
  const glm::ivec2 o = tileCorner(g, index, texels);
  for (int y = 0; y < texels + 2; ++y)
    for (int x = 0; x < texels + 2; ++x) atlas.at(o.x + x, o.y + y) = value;
}

// The captured irradiance of texel (x, y) of probe `index`'s tile, and its direction.
glm::vec3 irradianceTexel(const IrradianceVolume& v, int index, int x, int y) {
  const glm::ivec2 o = tileCorner(v.grid, index, v.grid.irradianceTexels);
  return v.irradiance.at(o.x + 1 + x, o.y + 1 + y);
}

glm::vec3 texelDirection(int x, int y, int texels) {
  const glm::vec2 uv = (glm::vec2(x, y) + 0.5f) / static_cast<float>(texels) * 2.0f - 1.0f;
  return shared::octahedralDecode(uv);
}

// A closed box [lo, hi] whose faces look outward (a solid object).
void addSolidBox(Scene& scene, glm::vec3 lo, glm::vec3 hi) {
  scene.materials.push_back(Material{});
  const int material = static_cast<int>(scene.materials.size()) - 1;
  const glm::vec3 size = hi - lo, center = 0.5f * (lo + hi);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      glm::vec3 corner = lo, u(0.0f), v(0.0f), outward(0.0f);
      corner[axis] = side ? hi[axis] : lo[axis];
      u[a] = size[a];
      v[b] = size[b];
      outward[axis] = side ? 1.0f : -1.0f;
      // addQuad turns the normal toward its `inside` point: one beyond the face.
      addQuad(scene, corner, u, v, material, center + 10.0f * outward * size);
    }
}

}  // namespace

TEST(IrradianceVolume, OctahedralTexelsCoverTheSphere) {
  for (const int n : {4, 8, 32}) {
    double total = 0.0;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) total += octahedralTexelSolidAngle(x, y, n);
    EXPECT_NEAR(total, 4.0 * std::numbers::pi, 1e-3) << n;
  }
  // The map's symmetry: the four corner texels (-Z) alike, the center ones (+Z) alike and
  // larger than the corners' (the octahedron's vertices are the least stretched).
  EXPECT_NEAR(octahedralTexelSolidAngle(0, 0, 8), octahedralTexelSolidAngle(7, 7, 8), 1e-9);
  EXPECT_NEAR(octahedralTexelSolidAngle(3, 3, 8), octahedralTexelSolidAngle(4, 4, 8), 1e-9);
}

TEST(IrradianceVolume, CaptureUnderAConstantSkyIsThatRadiance) {
  // E / pi = L for every normal, and every distance is "far".
  const glm::vec3 sky(0.5f, 0.25f, 1.0f);
  const VolumeBake env = bakeOfSky([&](glm::vec3) { return sky; });
  Scene scene;
  VolumeOptions options;
  options.captureSize = 16;
  CaptureOptions capture;
  capture.spp = 4;
  IrradianceVolume v = makeVolume({-1, -1, -1}, {1, 1, 1}, {1, 1, 1}, options, capture);
  captureVolumeProbes(scene, v, {0}, env.result, env.options);
  for (int y = 0; y < options.irradianceTexels; ++y)
    for (int x = 0; x < options.irradianceTexels; ++x) {
      const glm::vec3 e = irradianceTexel(v, 0, x, y);
      EXPECT_LT(maxRelativeError(e, sky), 1e-4) << x << "," << y;
    }
  const float far = 2.0f * glm::length(v.grid.spacing);
  EXPECT_NEAR(v.distance.at(5, 5).x, far, 1e-4f);
  EXPECT_NEAR(v.distance.at(5, 5).y, far * far, 1e-3f);
}

TEST(IrradianceVolume, CaptureUnderAHalfSkyIsTheSkyFactor) {
  // Radiance 1 above the horizon (+Y), 0 below: E / pi = (1 + n.y) / 2 in closed form. The
  // octahedral map's +Z center and the Y axis tell a swapped axis apart.
  const VolumeBake env = bakeOfSky([](glm::vec3 d) { return glm::vec3(d.y > 0.0f ? 1.0f : 0.0f); });
  Scene scene;
  VolumeOptions options;
  CaptureOptions capture;
  capture.spp = 16;
  IrradianceVolume v = makeVolume({-1, -1, -1}, {1, 1, 1}, {1, 1, 1}, options, capture);
  captureVolumeProbes(scene, v, {0}, env.result, env.options);
  const int n = options.irradianceTexels;
  double worst = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const glm::vec3 d = texelDirection(x, y, n);
      const float expected = 0.5f * (1.0f + d.y);
      worst =
          std::max(worst, static_cast<double>(std::abs(irradianceTexel(v, 0, x, y).y - expected)));
    }
  EXPECT_LT(worst, 0.01);
  // The lookup at the probe reads the same texels (a direction at a texel's center).
  const glm::vec3 up = texelDirection(3, 7, n);
  EXPECT_NEAR(lookupVolume(v, {0, 0, 0}, up, up, up).y, irradianceTexel(v, 0, 3, 7).y, 1e-5f);
}

TEST(IrradianceVolume, DistancesInsideASphereAreItsRadius) {
  const VolumeBake env = bakeOfSky([](glm::vec3) { return glm::vec3(1.0f); });
  Scene scene;
  scene.materials.push_back(Material{});
  scene.spheres.push_back(Sphere{glm::vec3(0.0f), 1.5f, 0});
  VolumeOptions options;
  options.captureSize = 16;
  CaptureOptions capture;
  capture.spp = 1;
  capture.bounces = 0;
  IrradianceVolume v = makeVolume({-1, -1, -1}, {1, 1, 1}, {1, 1, 1}, options, capture);
  captureVolumeProbes(scene, v, {0}, env.result, env.options);
  for (const glm::vec3& m : v.distance.pixels) {
    EXPECT_NEAR(m.x, 1.5f, 1e-3f);
    EXPECT_NEAR(m.y, 2.25f, 3e-3f);
  }
}

// The distance texel facing a wall 0.5 m away holds the mean distance over the cos^50 lobe
// around its direction (Majercik et al. 2019, 4.1): each direction meets the wall at 0.5 / cos
// or, leaving past it, the farthest distance; the mean is computed here by quadrature over the
// sphere. Over the cosine lobe instead it would be far larger (grazing rays reach far).
TEST(IrradianceVolume, DistanceTexelsAverageOverTheSharpLobe) {
  const VolumeBake env = bakeOfSky([](glm::vec3) { return glm::vec3(1.0f); });
  Scene scene;
  addSolidBox(scene, {-50.0f, -50.0f, -0.6f}, {50.0f, 50.0f, -0.5f});
  VolumeOptions options;
  options.captureSize = 32;
  CaptureOptions capture;
  capture.spp = 1;
  capture.bounces = 0;
  IrradianceVolume v = makeVolume({-1, -1, -1}, {1, 1, 1}, {1, 1, 1}, options, capture);
  captureVolumeProbes(scene, v, {0}, env.result, env.options);
  const glm::vec3 p = volumeProbePosition(v.grid, 0) + v.probes[0].offset;
  const float far = 2.0f * glm::length(v.grid.spacing);
  const int texels = v.grid.distanceTexels;
  const glm::ivec2 o = tileCorner(v.grid, 0, texels);
  int checked = 0;
  for (int y = 0; y < texels; ++y)
    for (int x = 0; x < texels; ++x) {
      const glm::vec3 n = texelDirection(x, y, texels);
      if (n.z > -0.9f) continue;  // the texels facing the wall
      double sum = 0.0, total = 0.0;
      constexpr int kTheta = 600, kPhi = 600;
      for (int i = 0; i < kTheta; ++i)
        for (int j = 0; j < kPhi; ++j) {
          const double theta = std::numbers::pi * (i + 0.5) / kTheta;
          const double phi = 2.0 * std::numbers::pi * (j + 0.5) / kPhi;
          const glm::dvec3 w(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                             std::cos(theta));
          const double c = glm::dot(glm::dvec3(n), w);
          if (c <= 0.0) continue;
          const double weight = std::pow(c, 50.0) * std::sin(theta);
          const double d = w.z < 0.0 ? std::min((p.z + 0.5) / -w.z, double{far}) : far;
          sum += weight * d;
          total += weight;
        }
      const float mean = v.distance.at(o.x + 1 + x, o.y + 1 + y).x;
      EXPECT_NEAR(mean, sum / total, 0.02 * sum / total) << x << " " << y;
      ++checked;
    }
  EXPECT_GT(checked, 0);
}

TEST(IrradianceVolume, RelocationMovesAProbeOutOfASolidBox) {
  Scene scene;
  addSolidBox(scene, glm::vec3(-0.5f), glm::vec3(0.5f));
  const glm::vec3 spacing(1.0f);
  // Near the +X face, inside: out through it, then a fifth of the spacing away from it.
  const ProbeRelocation near = relocateProbe(scene, {0.4f, 0.0f, 0.0f}, spacing);
  ASSERT_TRUE(near.on) << near.reason;
  const glm::vec3 moved = glm::vec3(0.4f, 0.0f, 0.0f) + near.offset;
  EXPECT_GT(moved.x, 0.5f + 0.19f);
  EXPECT_LE(glm::length(near.offset), 0.45f * std::sqrt(3.0f));
  EXPECT_LE(std::abs(near.offset.x), 0.45f + 1e-6f);
  // Close to a wall, outside: moved away to a fifth of the spacing.
  const ProbeRelocation close = relocateProbe(scene, {0.55f, 0.0f, 0.0f}, spacing);
  ASSERT_TRUE(close.on);
  EXPECT_NEAR(0.55f + close.offset.x, 0.7f, 0.02f);
  // In open space: where it is.
  EXPECT_EQ(relocateProbe(scene, {2.0f, 0.0f, 0.0f}, spacing).offset, glm::vec3(0.0f));
  // At the center, 0.5 from every face: no move within 0.45 of the spacing gets it out.
  const ProbeRelocation deep = relocateProbe(scene, {0.0f, 0.0f, 0.0f}, spacing);
  EXPECT_FALSE(deep.on);
  EXPECT_NE(deep.reason.find("inside geometry"), std::string::npos) << deep.reason;
}

TEST(IrradianceVolume, LookupOfAConstantFieldIsTheConstant) {
  // Whatever the weights (visibility, backface, relocation), they are normalized.
  IrradianceVolume v =
      makeVolume({0, 0, 0}, {3, 2, 3}, {3, 2, 3}, VolumeOptions{}, CaptureOptions{});
  const glm::vec3 c(0.7f, 0.3f, 0.1f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < volumeProbeCount(v.grid); ++i) {
    fillTile(v.irradiance, v.grid, i, v.grid.irradianceTexels, c);
    const float mean = 0.2f + u(rng);
    fillTile(v.distance, v.grid, i, v.grid.distanceTexels, {mean, mean * mean + 0.01f * u(rng), 0});
  }
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 p(3.0f * u(rng), 2.0f * u(rng), 3.0f * u(rng));
    const glm::vec3 n = glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
    EXPECT_LT(maxRelativeError(lookupVolume(v, p, n, n, n), c), 1e-5);
  }
}

TEST(IrradianceVolume, LookupReproducesALinearFieldThroughTheAtlases) {
  // Without the backface and visibility terms and the bias, each probe's tile holding the field
  // at the probe: the lookup is trilinear and returns the field at the point exactly (a wrong
  // tile, row or texel offset would not).
  IrradianceVolume v =
      makeVolume({-1, 0, 1}, {2, 1.5f, 4}, {3, 2, 4}, VolumeOptions{}, CaptureOptions{});
  v.grid.rules = 0;
  v.grid.normalBias = v.grid.viewBias = 0.0f;
  const auto field = [](glm::vec3 p) {
    return glm::vec3(1.0f + p.x, 2.0f - 0.5f * p.y + 0.25f * p.z, 0.5f + p.z);
  };
  for (int i = 0; i < volumeProbeCount(v.grid); ++i)
    fillTile(v.irradiance, v.grid, i, v.grid.irradianceTexels,
             field(volumeProbePosition(v.grid, i)));
  const glm::vec3 first = volumeProbePosition(v.grid, 0);
  const glm::vec3 last = volumeProbePosition(v.grid, volumeProbeCount(v.grid) - 1);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 300; ++i) {
    const glm::vec3 p = glm::mix(first, last, glm::vec3(u(rng), u(rng), u(rng)));
    const glm::vec3 n = glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
    const glm::vec3 got = lookupVolume(v, p, n, n, n);
    EXPECT_LT(glm::length(got - field(p)), 1e-4f) << p.x << "," << p.y << "," << p.z;
  }
}

TEST(IrradianceVolume, AFloorBetweenTwoLayersReadsTheLayerAboveIt) {
  // Probes at y = -0.25 (black, under the floor) and +0.25 (white), each seeing the floor at
  // 0.25. The point on the floor, biased up along its normal, is beyond the lower probes' floor
  // and nearer than the upper ones': it reads white. A bias of the wrong sign reads black.
  IrradianceVolume v = makeVolume({-0.25f, -0.5f, -0.25f}, {0.25f, 0.5f, 0.25f}, {1, 2, 1},
                                  VolumeOptions{}, CaptureOptions{});
  v.grid.rules = shared::kVolumeVisibility;
  v.grid.viewBias = 0.0f;
  v.grid.normalBias = 0.1f;
  fillTile(v.irradiance, v.grid, 0, v.grid.irradianceTexels, glm::vec3(0.0f));
  fillTile(v.irradiance, v.grid, 1, v.grid.irradianceTexels, glm::vec3(1.0f));
  for (const int i : {0, 1})
    fillTile(v.distance, v.grid, i, v.grid.distanceTexels, {0.25f, 0.0625f, 0.0f});
  const glm::vec3 up(0, 1, 0);
  EXPECT_GT(lookupVolume(v, {0, 0, 0}, up, up, up).x, 0.99f);
  // Relocation offsets move the probes: the same when both move sideways alike.
  v.probes[0].offset = v.probes[1].offset = glm::vec3(0.05f, 0.0f, 0.0f);
  EXPECT_GT(lookupVolume(v, {0, 0, 0}, up, up, up).x, 0.99f);
  // A probe switched off weighs nothing: with the upper one off, only the black one is left.
  v.probes[1].on = false;
  EXPECT_LT(lookupVolume(v, {0, 0, 0}, up, up, up).x, 1e-6f);
}

TEST(IrradianceVolume, FilesRoundTripAndBadFilesAreRefused) {
  IrradianceVolume v =
      makeVolume({0, 0, 0}, {2, 1, 2}, {2, 1, 2}, VolumeOptions{}, CaptureOptions{});
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  for (glm::vec3& p : v.irradiance.pixels) p = {u(rng), u(rng), u(rng)};
  for (glm::vec3& p : v.distance.pixels) p = {u(rng), u(rng), 0.0f};
  v.probes[1].offset = {0.1f, -0.2f, 0.3f};
  v.probes[2].on = false;
  v.probes[2].reason = "inside geometry: a test";
  const auto dir = std::filesystem::temp_directory_path() / "ibl_test_volume_files";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  writeVolume(v, dir);
  const IrradianceVolume r = loadVolume(dir);
  EXPECT_EQ(r.irradiance.pixels, v.irradiance.pixels);
  EXPECT_EQ(r.distance.pixels, v.distance.pixels);
  EXPECT_EQ(r.grid.counts, v.grid.counts);
  EXPECT_EQ(r.grid.origin, v.grid.origin);
  EXPECT_EQ(r.probes[1].offset, v.probes[1].offset);
  EXPECT_FALSE(r.probes[2].on);
  EXPECT_EQ(r.probes[2].reason, v.probes[2].reason);
  // A truncated atlas: the error names it.
  const auto atlas = dir / "distance.ktx2";
  std::filesystem::resize_file(atlas, std::filesystem::file_size(atlas) / 2);
  EXPECT_NE(errorOf([&] { loadVolume(dir); }).find("distance.ktx2"), std::string::npos);
  // No manifest: the directory is named.
  std::filesystem::remove(dir / "volume.json");
  EXPECT_NE(errorOf([&] { loadVolume(dir); }).find("not an irradiance volume"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(IrradianceVolume, SplitSumTakesItsDiffuseAndScalesTheSpecular) {
  // A white environment (E / pi = 1 everywhere, prefiltered 1): a volume of 1 changes nothing;
  // a volume of 2 doubles the diffuse, and doubles the specular through the irradiance ratio,
  // so the whole shading doubles (it is linear in both).
  BakeOptions options;
  const BakeResult bake = smallBake(options);
  SurfacePoint p;
  p.position = {1.0f, 0.5f, 1.0f};
  p.normal = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f));
  p.baseColor = {0.6f, 0.5f, 0.4f};
  p.metallic = 0.3f;
  p.roughness = 0.4f;
  const glm::vec3 view = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));
  RenderOptions o;
  o.mode = RenderMode::SplitSum;
  const glm::vec3 without = shadeSplitSum(p, view, bake, options, o);
  IrradianceVolume v =
      makeVolume({0, 0, 0}, {2, 1, 2}, {2, 1, 2}, VolumeOptions{}, CaptureOptions{});
  for (glm::vec3& d : v.distance.pixels) d = {10.0f, 100.0f, 0.0f};
  o.volume = &v;
  for (const float level : {1.0f, 2.0f}) {
    for (glm::vec3& e : v.irradiance.pixels) e = glm::vec3(level);
    EXPECT_LT(maxRelativeError(shadeSplitSum(p, view, bake, options, o), level * without), 2e-3)
        << level;
  }
  // Outside the volume's reach: the environment alone.
  p.position = {10.0f, 0.5f, 1.0f};
  EXPECT_LT(maxRelativeError(shadeSplitSum(p, view, bake, options, o), without), 1e-6);
}

TEST(IrradianceVolume, ScreenOcclusionKeepsToTheScaleTheProbesMiss) {
  IrradianceVolume v =
      makeVolume({0, 0, 0}, {4, 3, 4}, {8, 6, 16}, VolumeOptions{}, CaptureOptions{});
  ScreenAmbientOcclusionSettings s;
  s.enabled = true;
  // Spacing 0.5, 0.5 and 0.25: half the smallest.
  EXPECT_FLOAT_EQ(occlusionUnderVolume(s, &v).radius, 0.125f);
  EXPECT_EQ(occlusionUnderVolume(s, nullptr).radius, 0.0f);
  s.radius = 0.8f;  // the user's
  EXPECT_EQ(occlusionUnderVolume(s, &v).radius, 0.8f);
}
