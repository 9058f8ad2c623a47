// The probe workflow as a lighting artist meets it (docs/probes.md, "Captures as artists use
// them"): an open-top room with walls of several colors under data/hdri/park.exr, a metal
// sphere of roughness 0.1 beside the probe. The split sum with one probe against the path tracer
// (4 bounces), as the median and mean relative error of the luminance over the sphere's pixels,
// for the distant environment alone and for captures made as `ibl probe` makes them now and as
// it made them before: metals black in the capture, the sphere left out (--exclude), another
// diffuse model on either side (what `ibl render --probes` now refuses), the sky kept in the
// capture with no coverage (probes before the coverage was written). Then a Cornell box lit by
// its emissive ceiling alone: the share of black pixels and the noise at a few sample counts.
// Usage: ibl_probe_study [reference spp, default 512] [HDRI of data/hdri, default park]
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "ibl/env/environment.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/probe.hpp"
#include "support/helpers.hpp"
#include "support/probe_capture.hpp"
#include "support/room.hpp"
#include "support/sphere_renders.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

Material plain(glm::vec3 c) {
  Material m;
  m.baseColor = c;
  m.metallic = 0.0f;
  m.roughness = 0.8f;
  return m;
}

// The pixels whose center ray meets the sphere.
std::vector<bool> sphereMask(const Camera& camera, glm::vec3 center, float radius) {
  std::vector<bool> mask(static_cast<std::size_t>(camera.width) * camera.height, false);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray r = camera.generateRay(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const glm::vec3 o = r.origin - center;
      const float b = glm::dot(o, r.direction), c = glm::dot(o, o) - radius * radius;
      mask[static_cast<std::size_t>(y) * camera.width + x] = b * b - c > 0.0f && -b > 0.0f;
    }
  return mask;
}

struct Errors {
  double median = 0.0, mean = 0.0;
};
Errors relativeErrors(const Image& a, const Image& truth, const std::vector<bool>& mask) {
  std::vector<double> e;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) {
      const double t = luminance(truth.pixels[i]);
      e.push_back(std::abs(luminance(a.pixels[i]) - t) / std::max(t, 1e-6));
    }
  std::sort(e.begin(), e.end());
  Errors r;
  if (e.empty()) return r;
  r.median = e[e.size() / 2];
  for (double v : e) r.mean += v / static_cast<double>(e.size());
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const int spp = argc > 1 ? std::atoi(argv[1]) : 512;
  const std::string hdri = argc > 2 ? argv[2] : "park";
  Baked park;
  park.options.specular.size = 128;
  park.result = bakeEnvironment(loadEnvironment(hdriPath(hdri).string()).environment, park.options);

  // The open-top room: 4 x 2.5 x 4 m, its ceiling left out; a red, a green, a blue and two
  // grey walls, a light floor; a metal sphere of roughness 0.1 near the probe.
  RoomDescription room;
  const std::array<glm::vec3, 6> colors = {glm::vec3(0.8f, 0.15f, 0.1f),
                                           glm::vec3(0.1f, 0.6f, 0.2f),
                                           glm::vec3(0.7f),
                                           glm::vec3(0.5f),
                                           glm::vec3(0.15f, 0.25f, 0.8f),
                                           glm::vec3(0.5f)};
  for (int w = 0; w < 6; ++w) room.walls[w] = {plain(colors[w]), plain(0.8f * colors[w])};
  room.lo = glm::vec3(-2.0f, 0.0f, -2.0f);
  room.hi = glm::vec3(2.0f, 2.5f, 2.0f);
  Scene scene = makeRoom(room);
  // The ceiling's tiles are the third wall pair's second half: drop every mesh at y = hi.y.
  std::erase_if(scene.meshes, [&](const Mesh& m) {
    return std::all_of(m.positions.begin(), m.positions.end(),
                       [&](glm::vec3 p) { return p.y > room.hi.y - 1e-4f; });
  });
  Material metal;
  metal.baseColor = glm::vec3(0.95f, 0.93f, 0.88f);
  metal.metallic = 1.0f;
  metal.roughness = 0.1f;
  scene.materials.push_back(metal);
  const glm::vec3 sphereCenter(0.5f, 0.6f, 0.2f);
  const float sphereRadius = 0.45f;
  // As a mesh named "sphere", so that --exclude can leave it out.
  {
    Mesh m = tessellateSphere({sphereCenter, sphereRadius, 0}, 96);
    m.material = static_cast<int>(scene.materials.size()) - 1;
    m.names = {"sphere"};
    scene.meshes.push_back(std::move(m));
  }
  const glm::vec3 probeAt(0.0f, 1.2f, 0.0f);
  ProbePlacement placement;
  placement.position = probeAt;
  placement.hasProxy = true;
  placement.proxy = boxVolume(room.lo, room.hi);
  placement.influence = boxVolume(room.lo - glm::vec3(0.1f), room.hi + glm::vec3(0.1f));
  placement.fade = 0.1f;

  Camera camera;
  // From the side away from the probe: the sphere's reflections there are read through the
  // part of the probe where the sphere itself was captured.
  camera.from = glm::vec3(1.8f, 1.1f, 1.7f);
  camera.at = sphereCenter;
  camera.yfovDegrees = 32.0f;
  camera.width = 160;
  camera.height = 120;
  const std::vector<bool> mask = sphereMask(camera, sphereCenter, sphereRadius);

  RenderOptions reference;
  reference.mode = RenderMode::Reference;
  reference.spp = spp;
  reference.bounces = 4;
  const auto t0 = std::chrono::steady_clock::now();
  const RenderResult truth = renderScene(scene, camera, park.result, park.options, reference);
  fmt::print("reference: {} spp, {:.1f} s\n", spp,
             std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());

  CaptureOptions capture;
  capture.size = 64;
  capture.spp = 256;
  const auto probeWith = [&](const Scene& captured, const CaptureOptions& c) {
    return captureAndBakeProbe(captured, park.result, park.options, placement, c);
  };
  RenderOptions splitSum;
  splitSum.spp = 4;
  reference.diffuse = DiffuseModel::Lambert;
  const RenderResult lambertTruth =
      renderScene(scene, camera, park.result, park.options, reference);
  const auto row = [&](const std::string& what, const std::vector<LocalProbe>* probes,
                       DiffuseModel renderDiffuse) {
    RenderOptions o = splitSum;
    o.probes = probes;
    o.diffuse = renderDiffuse;
    const RenderResult r = renderScene(scene, camera, park.result, park.options, o);
    const Errors e = relativeErrors(
        r.color, renderDiffuse == DiffuseModel::Lambert ? lambertTruth.color : truth.color, mask);
    fmt::print("| {} | {:.3f} | {:.3f} |\n", what, e.median, e.mean);
  };
  fmt::print(
      "\nopen-top room under {}.exr, metal sphere r 0.1 beside the probe, split sum against "
      "the path tracer over the sphere's pixels\n| probe | median relative error | mean |\n| "
      "--- | --- | --- |\n",
      hdri);
  row("none (the distant environment)", nullptr, DiffuseModel::Disney);
  const std::vector<LocalProbe> now = {probeWith(scene, capture)};
  row("captured as `ibl probe` does (metals as diffuse F0, coverage)", &now, DiffuseModel::Disney);
  CaptureOptions black = capture;
  black.metalsAsDiffuse = false;
  const std::vector<LocalProbe> blackMetal = {probeWith(scene, black)};
  row("metals black in the capture", &blackMetal, DiffuseModel::Disney);
  const std::vector<LocalProbe> excluded = {
      probeWith(withoutObjects(scene, {"sphere"}, "--exclude"), capture)};
  row("the sphere left out (`--exclude sphere`)", &excluded, DiffuseModel::Disney);
  row("Lambert: captured Disney, rendered Lambert (now refused)", &now, DiffuseModel::Lambert);
  CaptureOptions lambert = capture;
  lambert.diffuse = DiffuseModel::Lambert;
  const std::vector<LocalProbe> lambertProbe = {probeWith(scene, lambert)};
  row("Lambert: captured and rendered Lambert", &lambertProbe, DiffuseModel::Lambert);
  // Before the coverage: the sky the probe saw kept in its radiance, composed with alpha 1.
  {
    const ProbeCapture c = captureProbe(scene, probeAt, park.result, park.options, capture);
    ProbeCapture old = c;
    for (int f = 0; f < kFaceCount; ++f)
      for (int y = 0; y < capture.size; ++y)
        for (int x = 0; x < capture.size; ++x) {
          const float sc = 2.0f * (static_cast<float>(x) + 0.5f) / capture.size - 1.0f;
          const float tc = 2.0f * (static_cast<float>(y) + 0.5f) / capture.size - 1.0f;
          const glm::vec3 d = glm::normalize(faceToDirection(f, sc, tc));
          const float sky = 1.0f - c.coverage.face(0, f).at(x, y).x;
          old.radiance.face(0, f).at(x, y) += sky * sampleBilinear(park.result.source, 0, d);
        }
    BakeOptions options;
    options.specular.size = capture.size;
    LocalProbe p = bakeProbe(old, placement, capture, options);
    p.coverageSpecular = CubeMap();
    p.coverageIrradiance = CubeMap();
    const std::vector<LocalProbe> before = {p};
    row("the sky kept in the capture, no coverage (before)", &before, DiffuseModel::Disney);
  }

  // The same room under a glass roof (a smooth thin pane tinted green, KHR_materials_transmission
  // 1): the probe sees the sky through it, tinted, where it used to see the glass as a black
  // surface (its diffuse, none) covering the whole roof.
  {
    Scene glazed = scene;
    Material glass;
    glass.baseColor = glm::vec3(0.75f, 0.95f, 0.85f);
    glass.metallic = 0.0f;
    glass.roughness = 0.0f;
    glass.transmission = 1.0f;
    glazed.materials.push_back(glass);
    addQuad(glazed, glm::vec3(room.lo.x, room.hi.y, room.lo.z),
            glm::vec3(room.hi.x - room.lo.x, 0.0f, 0.0f),
            glm::vec3(0.0f, 0.0f, room.hi.z - room.lo.z),
            static_cast<int>(glazed.materials.size()) - 1, probeAt);
    reference.diffuse = DiffuseModel::Disney;
    const RenderResult glazedTruth =
        renderScene(glazed, camera, park.result, park.options, reference);
    const auto glazedRow = [&](const std::string& what, const std::vector<LocalProbe>* probes) {
      RenderOptions o = splitSum;
      o.probes = probes;
      const RenderResult r = renderScene(glazed, camera, park.result, park.options, o);
      const Errors e = relativeErrors(r.color, glazedTruth.color, mask);
      fmt::print("| {} | {:.3f} | {:.3f} |\n", what, e.median, e.mean);
    };
    fmt::print(
        "\nthe room under a tinted glass roof\n| probe | median relative error | mean |\n"
        "| --- | --- | --- |\n");
    glazedRow("none (the distant environment)", nullptr);
    const std::vector<LocalProbe> through = {probeWith(glazed, capture)};
    glazedRow("captured through the glass, tinted (now)", &through);
    glazedRow("the glass left out of the capture (`--exclude`): the sky untinted", &now);
  }

  // A Cornell box lit by its emissive ceiling alone (the path tracer's closed box of
  // tests/render/test_path_tracer.cpp, a smaller lamp): black pixels and the time.
  fmt::print(
      "\nCornell box lit by an emissive ceiling quad (no environment), 96 x 96:\n| spp | "
      "black pixels | time |\n| --- | --- | --- |\n");
  Scene box;
  RoomDescription cornell;
  cornell.lo = glm::vec3(0.0f);
  cornell.hi = glm::vec3(1.0f);
  cornell.tiles = 1;
  const std::array<glm::vec3, 6> wallColors = {glm::vec3(0.63f, 0.065f, 0.05f),
                                               glm::vec3(0.14f, 0.45f, 0.09f),
                                               glm::vec3(0.73f),
                                               glm::vec3(0.73f),
                                               glm::vec3(0.73f),
                                               glm::vec3(0.73f)};
  for (int w = 0; w < 6; ++w) cornell.walls[w] = {plain(wallColors[w]), plain(wallColors[w])};
  box = makeRoom(cornell);
  Material lamp = plain(glm::vec3(0.0f));
  lamp.emissive = glm::vec3(15.0f);
  box.materials.push_back(lamp);
  addQuad(box, glm::vec3(0.4f, 0.999f, 0.4f), glm::vec3(0.2f, 0.0f, 0.0f),
          glm::vec3(0.0f, 0.0f, 0.2f), static_cast<int>(box.materials.size()) - 1, glm::vec3(0.5f));
  Camera inside;
  inside.from = glm::vec3(0.5f, 0.5f, 0.98f);
  inside.at = glm::vec3(0.5f, 0.5f, 0.0f);
  inside.yfovDegrees = 60.0f;
  inside.width = inside.height = 96;
  for (int n : {16, 256}) {
    RenderOptions o;
    o.mode = RenderMode::Reference;
    o.environmentLight = false;
    o.bounces = 4;
    o.spp = n;
    const RenderResult r = renderScene(box, inside, park.result, park.options, o);
    int dark = 0;
    for (const glm::vec3& p : r.color.pixels) dark += luminance(p) <= 0.0f;
    fmt::print("| {} | {:.1f} % | {:.2f} s |\n", n,
               100.0 * dark / static_cast<double>(r.color.pixels.size()), r.milliseconds / 1000.0);
  }
  return 0;
}
