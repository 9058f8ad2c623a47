// The error of the screen-space reflections against the reference renderer (the tables in
// docs/reflections.md): a glossy floor (roughness 0.05 and 0.3, metal and dielectric) with
// colored objects on it under data/hdri/park.exr, and Lagarde & de Rousiers' composition (4.9.5)
// in a room with a window: the distant environment, two nested local probes, the screen-space
// reflections, and all three. The path tracer is the truth; errors are mean relative errors over
// the floor's pixels (in the room, the relative L1 error of the luminance, over the floor and the
// frame). Also the time of the reflections on the
// CPU at 1280 x 720.
// Usage: ibl_reflections [reference spp, default 256]
#include <chrono>
#include <cstdlib>
#include <string>

#include <fmt/core.h>

#include "ibl/core/stats.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/probe.hpp"
#include "ibl/render/screen_space_reflections.hpp"
#include "support/probe_capture.hpp"
#include "support/shadow_scenes.hpp"
#include "support/sphere_renders.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// A red box, a green sphere and a blue metal sphere, on whatever floor material 0 is.
void addObjects(Scene& scene) {
  const int first = static_cast<int>(scene.materials.size());
  Material red, green, blue;
  red.baseColor = {0.8f, 0.1f, 0.1f};
  red.roughness = 0.6f;
  green.baseColor = {0.1f, 0.7f, 0.15f};
  green.roughness = 0.5f;
  blue.baseColor = {0.3f, 0.5f, 0.95f};
  blue.metallic = 1.0f;
  blue.roughness = 0.2f;
  scene.materials.insert(scene.materials.end(), {red, green, blue});
  addBox(scene, {-0.7f, 0.35f, -0.3f}, glm::vec3(0.35f), first);
  scene.spheres.push_back({{0.6f, 0.4f, -0.8f}, 0.4f, first + 1});
  scene.spheres.push_back({{0.2f, 0.3f, 0.5f}, 0.3f, first + 2});
}

Material floorMaterial(float roughness, bool metal) {
  Material m;
  m.baseColor = metal ? glm::vec3(0.9f) : glm::vec3(0.05f);
  m.metallic = metal ? 1.0f : 0.0f;
  m.roughness = roughness;
  return m;
}

Camera studyCamera(glm::vec3 from, glm::vec3 at, float fov) {
  Camera c;
  c.from = from;
  c.at = at;
  c.yfovDegrees = fov;
  c.width = 192;
  c.height = 144;
  return c;
}

// The pixels whose surface has the floor's roughness and faces up: the floor.
std::vector<float> floorMask(const Scene& scene, const Camera& camera, float roughness) {
  const ViewBuffers b = renderViewBuffers(scene, camera);
  const auto [forward, right, up] = camera.frame();
  std::vector<float> mask(b.positions.size(), 0.0f);
  for (std::size_t i = 0; i < mask.size(); ++i) {
    const glm::vec3 n = b.normals[i].x * right + b.normals[i].y * up + b.normals[i].z * forward;
    if (b.positions[i].z > 0.0f && b.roughness[i] == roughness && n.y > 0.99f) mask[i] = 1.0f;
  }
  return mask;
}

double meanRelative(const RenderResult& a, const RenderResult& reference,
                    const std::vector<float>* mask) {
  return compareImages(a.color, reference.color, mask).overall.meanRelativeError;
}

// The sum over the pixels of |luminance difference| over the reference's sum: in the room, whose
// dark pixels make per-pixel relative errors the reference's noise, the error of the light.
double relativeL1(const RenderResult& a, const RenderResult& reference,
                  const std::vector<float>* mask) {
  double difference = 0.0, total = 0.0;
  for (std::size_t i = 0; i < a.color.pixels.size(); ++i) {
    if (mask && (*mask)[i] <= 0.0f) continue;
    const double truth = luminance(reference.color.pixels[i]);
    difference += std::abs(luminance(a.color.pixels[i]) - truth);
    total += truth;
  }
  return difference / std::max(total, 1e-12);
}

Baked parkBake() {
  Baked b;
  b.options.specular.size = 128;
  b.result = bakeEnvironment(loadEnvironment(hdriPath("park").string()).environment, b.options);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  const int spp = argc > 1 ? std::atoi(argv[1]) : 256;
  const Baked park = parkBake();
  RenderOptions reference;
  reference.mode = RenderMode::Reference;
  reference.spp = spp;
  reference.bounces = 4;
  RenderOptions splitSum;
  splitSum.spp = 4;

  fmt::print(
      "A floor with a red box, a green sphere and a blue metal sphere on it under "
      "data/hdri/park.exr, 192 x 144; the split sum against the path tracer (4 bounces, {} spp), "
      "mean relative error over the floor's pixels\n\n",
      spp);
  fmt::print("| floor | roughness | probes alone | with SSR (medium) | with SSR (high) |\n");
  fmt::print("| --- | --- | --- | --- | --- |\n");
  const Camera open = studyCamera({0.3f, 1.4f, 3.4f}, {0.0f, 0.2f, -0.3f}, 45.0f);
  for (bool metal : {true, false})
    for (float roughness : {0.05f, 0.3f}) {
      Scene scene;
      scene.materials.push_back(floorMaterial(roughness, metal));
      addQuad(scene, {-4, 0, -4}, {8, 0, 0}, {0, 0, 8}, 0, {0, 1, 0});
      addObjects(scene);
      const std::vector<float> mask = floorMask(scene, open, roughness);
      const RenderResult truth = renderScene(scene, open, park.result, park.options, reference);
      const RenderResult none = renderScene(scene, open, park.result, park.options, splitSum);
      RenderOptions s = splitSum;
      s.screenReflections.enabled = true;
      const RenderResult medium = renderScene(scene, open, park.result, park.options, s);
      s.screenReflections.quality = ReflectionQuality::High;
      const RenderResult high = renderScene(scene, open, park.result, park.options, s);
      if (const char* dump = std::getenv("IBL_REFLECTION_IMAGES"))
        for (auto [name, image] :
             {std::pair{"reference", &truth}, std::pair{"none", &none}, std::pair{"ssr", &medium}})
          writeFileAtomic(
              std::filesystem::path(dump) /
                  fmt::format("{}_{}_{}.png", metal ? "metal" : "dielectric", roughness, name),
              encodePng(image->color, -1.0f));
      fmt::print("| {} | {} | {:.1f} % | {:.1f} % | {:.1f} % |\n",
                 metal ? "metal, base color 0.9" : "dielectric, base color 0.05", roughness,
                 100.0 * meanRelative(none, truth, &mask),
                 100.0 * meanRelative(medium, truth, &mask),
                 100.0 * meanRelative(high, truth, &mask));
    }

  // The composition: a 4 x 4 x 3 m room lit through a window by the park, a metal floor of
  // roughness 0.05, the objects; a probe over the room and a smaller one over the objects, both
  // captured with the objects in place (as a level's static geometry) and the surfaces' specular
  // (the floor is a mirror), proxies the room's box;
  // the influences reach past the walls and the floor, so that their fades fall outside.
  RoomDescription room;
  room.window = true;
  for (auto& wall : room.walls) {
    wall[0].baseColor = glm::vec3(0.7f, 0.65f, 0.55f);
    wall[1].baseColor = glm::vec3(0.35f, 0.45f, 0.6f);
    for (Material& m : wall) m.roughness = 0.7f;
  }
  room.walls[2][0] = floorMaterial(0.05f, true);
  room.walls[2][1] = floorMaterial(0.05f, true);
  Scene scene = makeRoom(room);
  addObjects(scene);
  CaptureOptions capture;
  capture.size = 64;
  capture.spp = 64;
  capture.bounces = 4;
  capture.specular = true;
  const ProbeVolume roomBox = boxVolume(room.lo, room.hi);
  const std::vector<LocalProbe> probes = {
      captureAndBakeProbe(scene, park.result, park.options,
                          placementAt({-0.1f, 0.7f, -0.2f}, roomBox,
                                      boxVolume({-1.4f, -0.3f, -1.5f}, {1.2f, 1.4f, 1.1f}), 0.3f),
                          capture),
      captureAndBakeProbe(
          scene, park.result, park.options,
          placementAt({0.0f, 1.5f, 0.0f}, roomBox,
                      boxVolume(room.lo - glm::vec3(0.3f), room.hi + glm::vec3(0.3f)), 0.2f),
          capture)};
  const Camera inside = studyCamera({1.5f, 1.7f, 1.8f}, {-0.3f, 0.3f, -0.6f}, 60.0f);
  const float floorRoughness = 0.05f;
  const std::vector<float> mask = floorMask(scene, inside, floorRoughness);
  const RenderResult truth = renderScene(scene, inside, park.result, park.options, reference);
  // The floor's pixels whose reflection the screen holds (alpha > 0.5 over the frame lit by the
  // probes): where the composition changes.
  std::vector<float> held = mask;
  {
    RenderOptions s = splitSum;
    s.probes = &probes;
    const ScreenReflections r = screenSpaceReflections(
        renderViewBuffers(scene, inside),
        renderScene(scene, inside, park.result, park.options, s).color, inside,
        reflectionParameters(ScreenReflectionSettings{}, glm::length(room.hi - room.lo)));
    for (std::size_t i = 0; i < held.size(); ++i)
      if (r.reflection[i].w <= 0.5f) held[i] = 0.0f;
  }
  fmt::print(
      "\nThe composition of Lagarde & de Rousiers 2014 (4.9.5) in a room lit through a window: "
      "a metal floor of roughness 0.05, the objects, two nested box probes (64^2, captured with "
      "the objects and the floor's specular); relative L1 error of the luminance against the path "
      "tracer ({} spp)\n\n",
      spp);
  fmt::print(
      "| reflections | over the floor where the screen holds the reflection | over the floor | "
      "over the frame |\n| --- | --- | --- | --- |\n");
  for (auto [name, useProbes, ssr] :
       {std::tuple{"distant environment", false, false},
        std::tuple{"screen-space reflections, then the distant environment", false, true},
        std::tuple{"two local probes, then the distant environment", true, false},
        std::tuple{"screen-space reflections, two local probes, the distant environment", true,
                   true}}) {
    RenderOptions s = splitSum;
    s.probes = useProbes ? &probes : nullptr;
    s.screenReflections.enabled = ssr;
    const RenderResult r = renderScene(scene, inside, park.result, park.options, s);
    if (const char* dump = std::getenv("IBL_REFLECTION_IMAGES")) {
      writeFileAtomic(std::filesystem::path(dump) / fmt::format("room_{}{}.png", useProbes, ssr),
                      encodePng(r.color, 2.0f));
      writeFileAtomic(std::filesystem::path(dump) / "room_reference.png",
                      encodePng(truth.color, 2.0f));
    }
    fmt::print("| {} | {:.1f} % | {:.1f} % | {:.1f} % |\n", name,
               100.0 * relativeL1(r, truth, &held), 100.0 * relativeL1(r, truth, &mask),
               100.0 * relativeL1(r, truth, nullptr));
  }

  {
    // The reflections of the reference's own frame: their error apart from the lit frame's.
    const ScreenReflections ofTruth = screenSpaceReflections(
        renderViewBuffers(scene, inside), truth.color, inside,
        reflectionParameters(ScreenReflectionSettings{}, glm::length(room.hi - room.lo)));
    RenderOptions s = splitSum;
    s.probes = &probes;
    s.screenReflection = &ofTruth;
    const RenderResult r = renderScene(scene, inside, park.result, park.options, s);
    fmt::print(
        "| the same, reflecting the path tracer's frame | {:.1f} % | {:.1f} % | {:.1f} % |\n",
        100.0 * relativeL1(r, truth, &held), 100.0 * relativeL1(r, truth, &mask),
        100.0 * relativeL1(r, truth, nullptr));
  }

  // The reflections' own time on the CPU at 1280 x 720 (the view buffers and the lit frame
  // given).
  Camera wide = open;
  wide.width = 1280;
  wide.height = 720;
  Scene floorScene;
  floorScene.materials.push_back(floorMaterial(0.05f, true));
  addQuad(floorScene, {-4, 0, -4}, {8, 0, 0}, {0, 0, 8}, 0, {0, 1, 0});
  addObjects(floorScene);
  const ViewBuffers buffers = renderViewBuffers(floorScene, wide);
  const Image lit(wide.width, wide.height, glm::vec3(1.0f));
  fmt::print(
      "\n| quality | screen-space reflections on the CPU, 1280 x 720 | pixels whose reflection "
      "the screen holds (alpha > 0.5) |\n| --- | --- | --- |\n");
  for (auto [quality, name] :
       {std::pair{ReflectionQuality::Low, "low"}, std::pair{ReflectionQuality::Medium, "medium"},
        std::pair{ReflectionQuality::High, "high"}}) {
    ScreenReflectionSettings settings;
    settings.quality = quality;
    const auto start = std::chrono::steady_clock::now();
    const ScreenReflections r =
        screenSpaceReflections(buffers, lit, wide, reflectionParameters(settings, 11.0f));
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::size_t reflected = 0;
    for (const glm::vec4& v : r.reflection) reflected += v.w > 0.5f ? 1 : 0;
    fmt::print("| {} | {:.0f} ms | {:.0f} % |\n", name, ms,
               100.0 * static_cast<double>(reflected) / static_cast<double>(r.reflection.size()));
  }
  return 0;
}
