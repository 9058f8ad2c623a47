// The error of the real-time shadows against the reference renderer (the shadow table in
// docs/lights.md): blockers over a floor under each light type, a spot in a closed room, the
// room of data/scenes (several lights), and the penumbra of a rect light; each with shadow maps
// and with ray-traced visibility (which leaves the light's own approximation alone). Also the
// time to build the maps.
// Usage: ibl_shadows [reference spp, default 256]
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

}  // namespace

int main(int argc, char** argv) {
  const int spp = argc > 1 ? std::atoi(argv[1]) : 256;
  const BlackBake bake = blackBake();
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
