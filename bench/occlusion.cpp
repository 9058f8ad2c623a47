// The error of the screen-space ambient occlusion against the reference renderer (the table in
// docs/occlusion.md): a sphere and a box in a room's corner under an environment, rendered by
// the path tracer (the truth, interreflections included), by the split sum without occlusion
// (what `ibl` did before), with GTAO at each quality, and with ray-traced occlusion (--ao, the
// screen-space term's own reference); and the visibility GTAO computes against the ray-traced
// visibility of the same radius. Also the time of GTAO on the CPU.
// Usage: ibl_occlusion [reference spp, default 512] [overcast (default), park (under
// data/hdri/park.exr), park-sun (its sun extracted as a light with shadow maps)]
#include <chrono>
#include <cstdlib>
#include <string>

#include <fmt/core.h>

#include "ibl/core/stats.hpp"
#include "ibl/env/sun_extraction.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/render/ambient_occlusion.hpp"
#include "support/shadow_scenes.hpp"
#include "support/sphere_renders.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// A room's corner: a 4 x 4 m floor, walls at x = -2 and z = -2 (3 m tall), a sphere of radius
// 0.4 m against both walls and a 0.6 m box beside it; grey, rough, dielectric, bar a metal sphere
// of roughness 0.3 (the specular occlusion).
Scene cornerScene() {
  Scene scene;
  Material grey;
  grey.baseColor = glm::vec3(0.6f);
  grey.roughness = 0.7f;
  Material metal;
  metal.baseColor = glm::vec3(0.9f, 0.7f, 0.5f);
  metal.metallic = 1.0f;
  metal.roughness = 0.3f;
  scene.materials = {grey, metal};
  const glm::vec3 inside(0.0f, 1.0f, 0.0f);
  addQuad(scene, {-2, 0, -2}, {4, 0, 0}, {0, 0, 4}, 0, inside);
  addQuad(scene, {-2, 0, -2}, {0, 3, 0}, {0, 0, 4}, 0, inside);
  addQuad(scene, {-2, 0, -2}, {4, 0, 0}, {0, 3, 0}, 0, inside);
  scene.spheres.push_back({{-1.55f, 0.4f, -1.55f}, 0.4f, 1});
  addBox(scene, {-0.5f, 0.3f, -1.6f}, {0.3f, 0.3f, 0.3f}, 0);
  return scene;
}

Camera cornerCamera() {
  Camera c;
  c.from = {1.6f, 1.5f, 1.9f};
  c.at = {-1.2f, 0.45f, -1.2f};
  c.yfovDegrees = 50.0f;
  c.width = 192;
  c.height = 144;
  return c;
}

double meanRelative(const RenderResult& a, const RenderResult& reference) {
  const std::vector<float> mask = interiorMask(a, reference);
  return compareImages(a.color, reference.color, &mask).overall.meanRelativeError;
}

}  // namespace

int main(int argc, char** argv) {
  const int spp = argc > 1 ? std::atoi(argv[1]) : 512;
  Scene scene = cornerScene();
  const Camera camera = cornerCamera();
  const auto [lo, hi] = scene.bounds();
  const float radius = 0.1f * glm::length(hi - lo);  // the default
  const std::string sky = argc > 2 ? argv[2] : "overcast";
  const bool real = sky == "park" || sky == "park-sun";
  const Baked park = real ? [&] {
    Baked b;
    b.options.specular.size = 128;
    Environment env = loadEnvironment(hdriPath("park").string()).environment;
    if (sky == "park-sun") {
      // The sun taken out of the panorama and lit as a light with shadows (Frostbite 4.9.2).
      const std::optional<ExtractedSun> sun = extractSun(env.equirect);
      if (sun) scene.lights.push_back(sun->light);
    }
    b.result = bakeEnvironment(env, b.options);
    return b;
  }()
                          : bakeOf([](glm::vec3 d) {
                              // The CIE overcast sky, (1 + 2 cos theta) / 3, over a dark ground.
                              return glm::vec3(d.y > 0.0f ? (1.0f + 2.0f * d.y) / 3.0f : 0.1f);
                            }, 128);
  RenderOptions o;
  o.mode = RenderMode::Reference;
  o.spp = spp;
  o.bounces = 4;
  const RenderResult reference = renderScene(scene, camera, park.result, park.options, o);
  o.mode = RenderMode::SplitSum;
  o.spp = 4;
  o.realTimeShadows = ShadowMode::Map;
  const RenderResult none = renderScene(scene, camera, park.result, park.options, o);
  const double base = meanRelative(none, reference);
  if (const char* dump = std::getenv("IBL_OCCLUSION_IMAGES")) {
    // The renders as PNG files, to look at.
    RenderOptions s = o;
    s.screenAmbientOcclusion.enabled = true;
    const RenderResult gtao = renderScene(scene, camera, park.result, park.options, s);
    for (auto [name, image] :
         {std::pair{"reference", &reference}, std::pair{"none", &none}, std::pair{"gtao", &gtao}})
      writeFileAtomic(std::filesystem::path(dump) / (std::string(name) + ".png"),
                      encodePng(image->color, -1.0f));
  }
  fmt::print(
      "A sphere and a box in a room's corner under {}, {} x {}; the split sum against the "
      "path tracer (4 bounces, {} spp), mean relative error over the pixels on the model; "
      "the default radius is {:.2f} m\n\n",
      sky == "park-sun" ? "data/hdri/park.exr, its sun extracted as a light with shadows"
      : real            ? "data/hdri/park.exr"
                        : "a CIE overcast sky",
      camera.width, camera.height, spp, radius);
  fmt::print(
      "| occlusion | radius | mean relative error | share of the error without occlusion "
      "|\n");
  fmt::print("| --- | --- | --- | --- |\n");
  fmt::print("| none | | {:.1f} % | 100 % |\n", 100.0 * base);
  for (float r : {radius, 1.5f, 3.0f}) {
    for (auto [quality, name] : {std::pair{AmbientOcclusionQuality::Low, "GTAO low (2 x 4)"},
                                 std::pair{AmbientOcclusionQuality::Medium, "GTAO medium (4 x 6)"},
                                 std::pair{AmbientOcclusionQuality::High, "GTAO high (8 x 8)"}}) {
      RenderOptions s = o;
      s.screenAmbientOcclusion.enabled = true;
      s.screenAmbientOcclusion.quality = quality;
      s.screenAmbientOcclusion.radius = r;
      const double e =
          meanRelative(renderScene(scene, camera, park.result, park.options, s), reference);
      fmt::print("| {} | {:.2f} m | {:.1f} % | {:.0f} % |\n", name, r, 100.0 * e, 100.0 * e / base);
    }
    RenderOptions t = o;
    t.aoRays = 256;
    t.aoDistance = r;
    const double e =
        meanRelative(renderScene(scene, camera, park.result, park.options, t), reference);
    fmt::print("| ray traced, 256 rays (--ao 256) | {:.2f} m | {:.1f} % | {:.0f} % |\n", r,
               100.0 * e, 100.0 * e / base);
  }

  // The visibility itself: GTAO against 1024 cosine-distributed rays to the same radius, read
  // from a diffuse-only render of a white-furnace (radiance 1) of albedo-0.001 Lambert: the
  // pixel's value over the albedo is the visibility (the multiple-bounce fit gives nothing back
  // at that albedo).
  Scene furnace = scene;
  furnace.lights.clear();
  for (Material& m : furnace.materials) {
    m.baseColor = glm::vec3(0.001f);
    m.metallic = 0.0f;
  }
  const Baked white = bakeOf([](glm::vec3) { return glm::vec3(1.0f); }, 32);
  RenderOptions f;
  f.spp = 1;
  f.only = ShadingTerms::Diffuse;
  f.diffuse = DiffuseModel::Lambert;
  f.aoRays = 1024;
  f.aoDistance = radius;
  const RenderResult traced = renderScene(furnace, camera, white.result, white.options, f);
  const ViewBuffers buffers = renderViewBuffers(scene, camera);
  fmt::print(
      "\nGTAO's visibility against 1024 rays per pixel to the same radius (mean |difference| "
      "over the pixels on the model), and its time on the CPU\n\n");
  fmt::print("| quality | mean abs. difference | GTAO on the CPU, {} x {} |\n", camera.width,
             camera.height);
  fmt::print("| --- | --- | --- |\n");
  for (auto [quality, name] : {std::pair{AmbientOcclusionQuality::Low, "low"},
                               std::pair{AmbientOcclusionQuality::Medium, "medium"},
                               std::pair{AmbientOcclusionQuality::High, "high"}}) {
    ScreenAmbientOcclusionSettings s;
    s.enabled = true;
    s.quality = quality;
    const auto start = std::chrono::steady_clock::now();
    const ScreenOcclusion ao = screenSpaceAmbientOcclusion(
        buffers, camera, ambientOcclusionParameters(s, glm::length(hi - lo)));
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < ao.visibility.size(); ++i) {
      if (traced.alpha[i] < 1.0f) continue;
      sum += std::abs(ao.visibility[i] - traced.color.pixels[i].y / 0.001f);
      ++count;
    }
    fmt::print("| {} | {:.3f} | {:.1f} ms |\n", name, sum / std::max(count, 1), ms);
  }
  return 0;
}
