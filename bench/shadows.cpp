// The error of the real-time shadows against the reference renderer (the shadow table in
// docs/lights.md): blockers over a floor under each light type, a spot in a closed room, the
// room of data/scenes (several lights), and the penumbra of a rect light; each with shadow maps
// and with ray-traced visibility (which leaves the light's own approximation alone); shadows
// through frosted glass, colored. Also the time to build the maps.
// Usage: ibl_shadows [reference spp, default 256] [glass: the shadows through glass alone]
#include <chrono>
#include <cstdlib>
#include <string>

#include <fmt/core.h>

#include "ibl/render/gltf.hpp"
#include "ibl/render/light.hpp"
#include "support/shadow_scenes.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

std::string row(const std::string& name, const ShadowError& map, const ShadowError& ray) {
  return fmt::format(
      "| {} | {:.1f} % | {:.2f} % / {:.1f} % | {:.3f} | {:.1f} % | {:.2f} % / {:.1f} % | {:.3f} | "
      "{:.1f} % |",
      name, 100.0 * map.referenceShadowed, 100.0 * map.stateMismatch, 100.0 * map.shadowMismatch,
      map.medianVisibility, 100.0 * map.relative, 100.0 * ray.stateMismatch,
      100.0 * ray.shadowMismatch, ray.medianVisibility, 100.0 * ray.relative);
}

RenderOptions optionsFor(ShadowMode mode) {
  RenderOptions o;
  o.realTimeShadows = mode;
  o.spp = 4;
  return o;
}

// Glass over a white floor (the camera under it, looking down at the floor), lit by a sun 30
// degrees from the zenith and 5 degrees wide: a frosted pane (thin, roughness 0.3, orange), a
// frosted slab (0.2 m of glass that keeps (0.3, 0.7, 0.9) after 0.5 m), a frosted ball (0.3 m
// across as thick, the same glass) and a smooth pane (the first, roughness 0: the light goes on
// unbent, as the straight shadows have it). `withGlass` false: the floor alone.
Scene glassOverFloor(int kind, bool withGlass) {
  Material floor;
  floor.baseColor = glm::vec3(0.8f);
  floor.metallic = 0.0f;
  floor.roughness = 1.0f;
  Material glass;
  const bool pane = kind == 0 || kind == 3;
  glass.baseColor = pane ? glm::vec3(0.9f, 0.5f, 0.2f) : glm::vec3(1.0f);
  glass.metallic = 0.0f;
  glass.roughness = kind == 3 ? 0.0f : 0.3f;
  glass.transmission = 1.0f;
  if (!pane) {
    glass.thickness = kind == 1 ? 0.2f : 0.6f;
    glass.attenuationColor = {0.3f, 0.7f, 0.9f};
    glass.attenuationDistance = 0.5f;
  }
  Scene s;
  s.materials = {floor, glass};
  s.meshes.push_back(planeMesh(3.0f));
  if (withGlass) {
    if (pane)
      addQuad(s, {-0.4f, 1.0f, -0.4f}, {0.8f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.8f}, 1,
              {0.0f, 2.0f, 0.0f});
    else if (kind == 1)
      addBox(s, {0.0f, 1.0f, 0.0f}, {0.4f, 0.1f, 0.4f}, 1);
    else
      s.spheres.push_back({glm::vec3(0.0f, 1.2f, 0.0f), 0.3f, 1});
  }
  Light sun = shadowStudyLight(LightType::Sun);
  sun.direction = {0.5f, 0.8660254f, 0.0f};
  sun.angularDiameter = 0.0872665f;
  s.lights = {sun};
  return s;
}

// What reaches the floor through the glass, per channel, over the pixels of the floor that the
// straight shadow covers (the split sum's ray-traced visibility below 0.95): the reference's
// (4 bounces, `spp` samples; the light the glass scatters, refracts and absorbs) and the real-time
// paths' (each as its render with the glass over its render without).
void glassShadows(const BlackBake& bake, int spp) {
  fmt::print(
      "\nShadows through glass (frosted: roughness 0.3) on the floor below, a sun 5 degrees wide "
      "30 degrees from the zenith; what passes per channel (R, G, B) over the straight shadow, and "
      "the median per-pixel error of its luminance against the reference ({} spp, 4 bounces)\n\n",
      spp);
  fmt::print("| glass | reference | map | ray | map: median error | ray: median error |\n");
  fmt::print("| --- | --- | --- | --- | --- | --- |\n");
  const char* names[] = {"thin pane, orange", "slab 0.2 m, absorbing", "ball 0.6 m, absorbing",
                         "smooth thin pane, orange"};
  // The floor where the shadows fall, tan 30 degrees of the glass's height toward -X.
  Camera camera = topDownCamera(glm::vec3(-0.6f, 0.0f, 0.0f), 1.6f, 64);
  camera.from = {-0.6f, 0.5f, 0.0f};  // below the glass
  for (int kind = 0; kind < 4; ++kind) {
    RenderOptions o;
    o.environmentLight = false;
    o.backgroundEnvironment = false;
    o.cameraSeesEmitters = false;
    o.spp = spp;
    o.mode = RenderMode::Reference;
    o.bounces = 4;
    const auto render = [&](bool glass, const RenderOptions& options) {
      return renderScene(glassOverFloor(kind, glass), camera, bake.result, bake.options, options);
    };
    const RenderResult ref = render(true, o), refOpen = render(false, o);
    o.mode = RenderMode::SplitSum;
    o.spp = 4;
    o.realTimeShadows = ShadowMode::Map;
    const RenderResult map = render(true, o);
    o.realTimeShadows = ShadowMode::Ray;
    o.shadowSettings.raySamples = 64;
    const RenderResult ray = render(true, o), open = render(false, o);
    glm::dvec3 sums[3]{};
    glm::dvec3 openSum(0.0), refOpenSum(0.0);
    std::vector<double> mapError, rayError;
    for (std::size_t i = 0; i < ray.color.pixels.size(); ++i) {
      const double straight = luminance(ray.color.pixels[i]) / luminance(open.color.pixels[i]);
      if (!(straight < 0.95)) continue;
      sums[0] += glm::dvec3(ref.color.pixels[i]);
      sums[1] += glm::dvec3(map.color.pixels[i]);
      sums[2] += glm::dvec3(ray.color.pixels[i]);
      openSum += glm::dvec3(open.color.pixels[i]);
      refOpenSum += glm::dvec3(refOpen.color.pixels[i]);
      const double r = luminance(ref.color.pixels[i]) / luminance(refOpen.color.pixels[i]);
      mapError.push_back(
          std::abs(luminance(map.color.pixels[i]) / luminance(open.color.pixels[i]) - r) / r);
      rayError.push_back(std::abs(straight - r) / r);
    }
    const auto rgb = [](glm::dvec3 v) {
      return fmt::format("{:.3f}, {:.3f}, {:.3f}", v.x, v.y, v.z);
    };
    fmt::print("| {} | {} | {} | {} | {:.1f} % | {:.1f} % |\n", names[kind],
               rgb(sums[0] / refOpenSum), rgb(sums[1] / openSum), rgb(sums[2] / openSum),
               100.0 * median(mapError), 100.0 * median(rayError));
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int spp = argc > 1 ? std::atoi(argv[1]) : 256;
  const BlackBake bake = blackBake();
  if (argc > 2 && std::string(argv[2]) == "glass") {
    glassShadows(bake, spp);
    return 0;
  }
  fmt::print(
      "Shadows against the reference (--bounces 0 --shadows ray, {} spp), 1024-texel maps; "
      "lit pixels compared; state: visibility above or below 1/2\n\n",
      spp);
  fmt::print(
      "| scene | shadowed (reference) | map: state differs, of all / of the shadow | map: median "
      "Δv | map: radiance error | ray: state differs | ray: median Δv | ray: radiance error |\n");
  fmt::print("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
  const auto study = [&](const std::string& name, const Scene& scene, const Camera& camera) {
    const ShadowError map =
        compareShadows(renderShadowStudy(scene, camera, bake, optionsFor(ShadowMode::Map), spp));
    const ShadowError ray =
        compareShadows(renderShadowStudy(scene, camera, bake, optionsFor(ShadowMode::Ray), spp));
    fmt::print("{}\n", row(name, map, ray));
  };
  for (LightType type : {LightType::Point, LightType::Spot, LightType::Sun, LightType::Sphere,
                         LightType::Disk, LightType::Tube, LightType::Rect})
    study(fmt::format("{}, sphere and box over a floor", lightTypeName(type)),
          blockersOverFloor(shadowStudyLight(type)), floorCamera(128));
  study("spot in a closed room", spotInRoom(), roomCamera(128));
  study("sun over a field, poles 3-16 m away", polesOnAField(), fieldCamera(256, 128));
  {
    const std::filesystem::path dir = std::filesystem::path(IBL_SOURCE_DIR) / "data/scenes";
    Scene room = loadGltf((dir / "room.gltf").string());
    for (const Light& l : readLightsFile(dir / "room_lights.json")) room.lights.push_back(l);
    Camera c;
    c.from = {2.2f, 2.2f, 3.4f};
    c.at = {-0.2f, 0.6f, -0.6f};
    c.yfovDegrees = 65.0f;
    c.width = 192;
    c.height = 144;
    study("data/scenes/room.gltf (spot, point, rect)", room, c);
  }
  // The penumbra.
  {
    const int n = 128;
    const double perPixel = 3.0 / n;
    const Scene scene = penumbraScene();
    const ShadowStudy map =
        renderShadowStudy(scene, wallCamera(n), bake, optionsFor(ShadowMode::Map), spp);
    const ShadowStudy ray =
        renderShadowStudy(scene, wallCamera(n), bake, optionsFor(ShadowMode::Ray), spp);
    fmt::print(
        "\nPenumbra of a 0.6 m blocker 0.5 m before a wall, 1.2 x 0.6 m rect light 2 m away (10 to "
        "90 % visibility): reference {:.3f} m, map {:.3f} m, ray {:.3f} m\n",
        penumbraWidth(visibilityOf(map.reference, map.referenceOpen), n, n, perPixel),
        penumbraWidth(visibilityOf(map.fast, map.fastOpen), n, n, perPixel),
        penumbraWidth(visibilityOf(ray.fast, ray.fastOpen), n, n, perPixel));
  }
  glassShadows(bake, spp);
  // Building the maps.
  fmt::print("\nBuilding the maps (Embree, every core):\n");
  for (int size : {512, 1024, 2048}) {
    ShadowSettings settings;
    settings.mapSize = size;
    for (LightType type : {LightType::Sun, LightType::Spot, LightType::Point}) {
      const Scene scene = blockersOverFloor(shadowStudyLight(type));
      const ShadowMapBuilder builder(scene);
      const Camera camera = floorCamera(64);
      builder.build(scene.lights, &camera, settings);  // warm up
      const auto start = std::chrono::steady_clock::now();
      const ShadowMaps maps = builder.build(scene.lights, &camera, settings);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      fmt::print("  {} texels, {} ({} layers): {:.1f} ms\n", size, lightTypeName(type),
                 maps.layers.size(), ms);
    }
  }
  return 0;
}
