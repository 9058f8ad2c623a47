// The opaque frame that the split sum reads behind transmissive surfaces
// (ibl/render/transmission_frame.hpp; the glTF Sample Viewer's approximation of
// KHR_materials_transmission and _volume): its chain halved as Vulkan's linear blits halve it,
// against values worked by hand; a thin wall showing what lies behind it, against the closed
// form; a solid slab showing the floor under it displaced to where the refracted ray leaves it,
// against Snell's law worked out here from the angles.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/render/camera.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/render/transmission_frame.hpp"
#include "support/helpers.hpp"
#include "support/sphere_renders.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// A level of w x h texels whose texel (x, y) is value(x, y).
template <typename F>
FrameLevel levelOf(int w, int h, F value) {
  FrameLevel l;
  l.width = w;
  l.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) l.texels.push_back(value(x, y));
  return l;
}

void expectTexel(glm::vec4 got, glm::vec4 expected, const char* what) {
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(got[k], expected[k], 1e-6f) << what << ", channel " << k;
}

// A square of side 2 * half in the plane z = height, facing +Z, of material `material`.
Mesh squareAt(float height, float half, int material, float x0 = -1.0f, float x1 = 1.0f) {
  Mesh m;
  m.positions = {{x0 * half, -half, height},
                 {x1 * half, -half, height},
                 {x1 * half, half, height},
                 {x0 * half, half, height}};
  m.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = material;
  return m;
}

// A surface that shows its emission alone: black, no specular layer.
Material emitter(glm::vec3 radiance) {
  Material m;
  m.baseColor = glm::vec3(0.0f);
  m.metallic = 0.0f;
  m.specular = 0.0f;
  m.emissive = radiance;
  return m;
}

// No light at all: what the pixels show comes from the emitters through the glass.
const Baked& darkness() {
  static const Baked b = bakeOf([](glm::vec3) { return glm::vec3(0.0f); }, 16);
  return b;
}

}  // namespace

// Halving: where a side is even, each texel is the mean of the 2 x 2 above it; where it is odd,
// the linear blit reads the upper level at the lower texel's center, scaled: from 3 texels to 1,
// the middle one.
TEST(TransmissionFrame, LevelsHalveAsLinearBlits) {
  const FrameLevel even = levelOf(4, 2, [](int x, int y) {
    return glm::vec4(static_cast<float>(x + 4 * y), 1.0f, 0.0f, static_cast<float>(x % 2));
  });
  const FrameLevel half = halveFrameLevel(even);
  ASSERT_EQ(half.width, 2);
  ASSERT_EQ(half.height, 1);
  // (0 + 1 + 4 + 5) / 4 and (2 + 3 + 6 + 7) / 4; the coverage 0, 1, 0, 1 averages to 0.5.
  expectTexel(half.texels[0], glm::vec4(2.5f, 1.0f, 0.0f, 0.5f), "left");
  expectTexel(half.texels[1], glm::vec4(4.5f, 1.0f, 0.0f, 0.5f), "right");
  const FrameLevel odd =
      levelOf(3, 3, [](int x, int y) { return glm::vec4(static_cast<float>(x * x + 10 * y)); });
  const FrameLevel one = halveFrameLevel(odd);
  ASSERT_EQ(one.width, 1);
  ASSERT_EQ(one.height, 1);
  expectTexel(one.texels[0], glm::vec4(11.0f), "3 x 3 to 1 x 1");
  // 5 x 1 to 2 x 1: centers at 1.25 and 3.75 (the texels' centers at 0.5, 1.5, ...), three
  // quarters of the way from texel 0 to 1 and a quarter from texel 3 to 4.
  const FrameLevel five =
      levelOf(5, 1, [](int x, int) { return glm::vec4(static_cast<float>(x * x)); });
  const FrameLevel two = halveFrameLevel(five);
  expectTexel(two.texels[0], glm::vec4(0.25f * 0.0f + 0.75f * 1.0f), "5 to 2, left");
  expectTexel(two.texels[1], glm::vec4(0.75f * 9.0f + 0.25f * 16.0f), "5 to 2, right");
}

// The frame of a camera: a chain down to 1 x 1 (64 x 48: 7 levels), its last level the mean of
// the first where every halving is even; uvOf places the point looked at in the middle and a
// point on the right edge of the view at u = 1; sample blends the levels linearly between them.
TEST(TransmissionFrame, ChainProjectionAndTrilinearLookup) {
  Camera c;
  c.width = 64;
  c.height = 48;
  c.perspective = false;
  c.orthoWidth = 8.0f;
  c.from = glm::vec3(0.0f, 0.0f, 5.0f);
  Image color(64, 48);
  std::vector<float> coverage(64 * 48, 1.0f);
  double sum = 0.0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      color.at(x, y) = glm::vec3(static_cast<float>(x), static_cast<float>(y), 1.0f);
      sum += x;
    }
  const TransmissionFrame f = transmissionFrameOf(color, coverage, c);
  ASSERT_EQ(f.levels.size(), 7u);
  EXPECT_EQ(f.levels[6].width, 1);
  EXPECT_EQ(f.levels[6].height, 1);
  EXPECT_EQ(f.levels[4].width, 4);
  EXPECT_EQ(f.levels[4].height, 3);
  const glm::vec2 center = f.uvOf(glm::vec3(0.0f, 0.0f, -3.0f));
  EXPECT_NEAR(center.x, 0.5f, 1e-6f);
  EXPECT_NEAR(center.y, 0.5f, 1e-6f);
  const glm::vec2 right = f.uvOf(glm::vec3(4.0f, 3.0f, 0.0f));  // the view is 8 x 6
  EXPECT_NEAR(right.x, 1.0f, 1e-6f);
  EXPECT_NEAR(right.y, 0.0f, 1e-6f) << "v grows downward";
  // Level 0 at the center: between texels 31 and 32 across.
  EXPECT_NEAR(f.sample(center, 0.0f).x, 31.5f, 1e-4f);
  // Halfway between levels 0 and 1: 31.5 on both at the center (their means agree there).
  EXPECT_NEAR(f.sample(center, 0.5f).x, 31.5f, 1e-4f);
  // The last level, and beyond it, is the mean of the first except at the uneven 4 x 3 halving.
  EXPECT_NEAR(f.sample(center, 6.0f).x, sum / (64.0 * 48.0), 0.5);
  EXPECT_FLOAT_EQ(f.sample(center, 6.0f).x, f.sample(center, 40.0f).x);
  // Near the left edge, level 0 clamps: the first column.
  EXPECT_NEAR(f.sample(glm::vec2(0.0f, 0.5f), 0.0f).x, 0.0f, 1e-6f);
  // Halfway between two levels at a point where they differ: their mean.
  const glm::vec2 q(0.3f, 0.7f);
  const float l0 = sampleFrameLevel(f.levels[0], q).y, l1 = sampleFrameLevel(f.levels[1], q).y;
  EXPECT_NEAR(f.sample(q, 0.5f).y, 0.5f * (l0 + l1), 1e-4f);
  EXPECT_THROW(transmissionFrameOf(Image(3, 3), std::vector<float>(9), c), Error);
}

// A perspective camera's frame holds nothing at or behind the camera's plane: a point there reads
// as uncovered (where projecting it would mirror it onto the frame), a point in front reads the
// frame.
TEST(TransmissionFrame, NothingBehindAPerspectiveCamera) {
  Camera c;
  c.width = c.height = 8;
  c.from = glm::vec3(0.0f, 0.0f, 5.0f);
  const TransmissionFrame f =
      transmissionFrameOf(Image(8, 8, glm::vec3(1.0f)), std::vector<float>(64, 1.0f), c);
  EXPECT_FLOAT_EQ(f.at(glm::vec3(0.1f, 0.1f, 0.0f), 0.0f).w, 1.0f) << "in front";
  EXPECT_FLOAT_EQ(f.at(glm::vec3(0.1f, 0.1f, 7.0f), 0.0f).w, 0.0f) << "behind";
  EXPECT_FLOAT_EQ(f.at(glm::vec3(0.1f, 0.1f, 5.0f), 0.0f).w, 0.0f) << "on the camera's plane";
}

namespace {

// A smooth thin wall (transmission 1) of base color `tint` in the plane z = 0, 100 wide, over a
// floor that emits `emitted` at z = floorHeight; and an orthographic view 0.5 wide straight down
// at them, 4 x 4 pixels.
Scene wallOverFloor(glm::vec3 tint, glm::vec3 emitted, float floorHeight) {
  Material wall;
  wall.baseColor = tint;
  wall.metallic = 0.0f;
  wall.roughness = 0.0f;
  wall.transmission = 1.0f;
  Scene scene;
  scene.materials = {wall, emitter(emitted)};
  scene.meshes = {squareAt(0.0f, 50.0f, 0), squareAt(floorHeight, 50.0f, 1)};
  return scene;
}
Camera downOntoTheWall() {
  Camera c;
  c.perspective = false;
  c.orthoWidth = 0.5f;
  c.from = glm::vec3(0.0f, 0.0f, 3.0f);
  c.width = c.height = 4;
  return c;
}

}  // namespace

// A smooth thin wall of base color c in front of a surface that emits E, no other light: the
// camera sees (1 - F0) c E through it at normal incidence, in the split sum as in the reference
// (before the opaque frame, the split sum saw the black environment there: 0).
TEST(TransmissionFrame, ThinWallShowsWhatLiesBehindIt) {
  const glm::vec3 tint(0.2f, 0.5f, 0.8f), emitted(2.0f, 3.0f, 4.0f);
  const Scene scene = wallOverFloor(tint, emitted, -1.0f);
  for (RenderMode mode : {RenderMode::Reference, RenderMode::SplitSum}) {
    RenderOptions o;
    o.mode = mode;
    o.spp = mode == RenderMode::Reference ? 64 : 1;
    o.bounces = 4;
    const Image img =
        renderScene(scene, downOntoTheWall(), darkness().result, darkness().options, o).color;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(img.at(1, 2)[k], 0.96f * tint[k] * emitted[k], 0.01f * emitted[k])
          << (mode == RenderMode::Reference ? "reference" : "split sum") << ", channel " << k;
  }
}

// A thin wall lying on an emitting floor, in its plane (a glass resting on a table): the floor
// behind it is still the opaque frame's, seen through the wall as through one a unit above it;
// a frame that steps past each transmissive surface along the view would step past the floor
// too and show nothing.
TEST(TransmissionFrame, WallOnTheFloorShowsTheFloor) {
  const glm::vec3 tint(0.2f, 0.5f, 0.8f), emitted(2.0f, 3.0f, 4.0f);
  RenderOptions o;
  o.spp = 1;
  for (float height : {-1.0f, 0.0f}) {
    const Image img = renderScene(wallOverFloor(tint, emitted, height), downOntoTheWall(),
                                  darkness().result, darkness().options, o)
                          .color;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(img.at(1, 2)[k], 0.96f * tint[k] * emitted[k], 0.01f * emitted[k])
          << "the floor at " << height << ", channel " << k;
  }
}

// A smooth slab of index 1.5 and thickness 2 over a floor that emits red for x < 2.6 and blue
// beyond, seen at 45 degrees by an orthographic camera: each pixel shows the floor where the view's
// ray, refracted into the slab (sin t = sin 45 / 1.5) and run for the thickness, leaves it, then
// on along the view. Without the exit's offset the edge between red and blue moves 9 pixels.
TEST(TransmissionFrame, SlabShowsTheFloorWhereTheRefractedRayLeaves) {
  Material glass;
  glass.baseColor = glm::vec3(1.0f);
  glass.metallic = 0.0f;
  glass.roughness = 0.0f;
  glass.transmission = 1.0f;
  glass.thickness = 2.0f;
  glass.ior = 1.5f;
  Scene scene;
  scene.materials = {glass, emitter({1.0f, 0.0f, 0.0f}), emitter({0.0f, 0.0f, 1.0f})};
  Mesh bottom = squareAt(-2.0f, 50.0f, 0);
  bottom.normals.assign(4, glm::vec3(0.0f, 0.0f, -1.0f));
  bottom.indices = {0, 2, 1, 0, 3, 2};
  scene.meshes = {squareAt(0.0f, 50.0f, 0), bottom, squareAt(-3.0f, 50.0f, 1, -1.0f, 0.052f),
                  squareAt(-3.0f, 50.0f, 2, 0.052f, 1.0f)};
  Camera c;
  c.perspective = false;
  c.orthoWidth = 0.125f;
  c.from = glm::vec3(-3.0f, 0.0f, 3.0f);
  c.up = glm::vec3(0.0f, 0.0f, 1.0f);
  c.width = 2;
  c.height = 64;  // 4 units tall, 1 / 16 per pixel
  RenderOptions o;
  o.spp = 1;
  const Image img = renderScene(scene, c, darkness().result, darkness().options, o).color;
  const float sinT = std::sin(0.25f * 3.14159265f) / 1.5f, cosT = std::sqrt(1.0f - sinT * sinT);
  int checked = 0;
  for (int y = 0; y < c.height; ++y) {
    const Ray ray = c.generateRay(0.5f, static_cast<float>(y) + 0.5f);
    const glm::vec3 entry = ray.origin - (ray.origin.z / ray.direction.z) * ray.direction;
    const glm::vec3 along = glm::normalize(glm::vec3(ray.direction.x, ray.direction.y, 0.0f));
    const glm::vec3 exit = entry + 2.0f * (sinT * along + glm::vec3(0.0f, 0.0f, -cosT));
    const float floorX = exit.x + ray.direction.x * (exit.z + 3.0f) / -ray.direction.z - 2.6f;
    if (std::abs(floorX) < 0.2f) continue;  // within 2 pixels of the edge, as the floor sees them
    const glm::vec3 p = img.at(0, y);
    ++checked;
    if (floorX < 0.0f)
      EXPECT_GT(p.x, 10.0f * p.z) << "row " << y << " should be red, floor x " << floorX + 2.6f;
    else
      EXPECT_GT(p.z, 10.0f * p.x) << "row " << y << " should be blue, floor x " << floorX + 2.6f;
  }
  EXPECT_GT(checked, 50);
}

// A rough thin wall (roughness 1, index 1.25: transmissionRoughness 0.5) before an emitter that
// covers the left half of a 64 x 32 view, no other light: the wall reads the frame at level
// log2(64) x 0.5 = 3 (8 x 8 pixels a texel), so a pixel sees the share of that level's bilinear
// footprint the emitter covers, worked here from the texels' centers (at 4, 12, ..., 60): 1 at
// column 16, 0.6875 at 30 (texel 3 covered, 4 not: 30.5 / 8 - 0.5 = 3.3125), 0.3125 at 33, 0 at
// 40; as a ratio to the same wall before an emitter that covers the whole view. A level of
// log2(64) x 1 (the roughness without the index's scaling) gives 0.5 everywhere, the coverage
// mixed in rather than premultiplied its square.
TEST(TransmissionFrame, RoughWallReadsTheLevelOfItsRoughness) {
  Material wall;
  wall.baseColor = glm::vec3(1.0f);
  wall.metallic = 0.0f;
  wall.roughness = 1.0f;
  wall.ior = 1.25f;
  wall.transmission = 1.0f;
  Camera c;
  c.perspective = false;
  c.orthoWidth = 4.0f;
  c.from = glm::vec3(0.0f, 0.0f, 3.0f);
  c.width = 64;
  c.height = 32;
  RenderOptions o;
  o.spp = 1;
  const auto render = [&](float right) {
    Scene scene;
    scene.materials = {wall, emitter(glm::vec3(1.0f, 2.0f, 3.0f))};
    scene.meshes = {squareAt(0.0f, 50.0f, 0), squareAt(-1.0f, 50.0f, 1, -1.0f, right)};
    return renderScene(scene, c, darkness().result, darkness().options, o).color;
  };
  const Image half = render(0.0f), full = render(1.0f);
  const std::pair<int, float> expected[] = {{16, 1.0f}, {30, 0.6875f}, {33, 0.3125f}, {40, 0.0f}};
  for (const auto& [column, share] : expected) {
    ASSERT_GT(full.at(column, 16).z, 0.05f) << "the wall passes some light";
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(half.at(column, 16)[k] / full.at(column, 16)[k], share, 1e-3f)
          << "column " << column << ", channel " << k;
  }
}
