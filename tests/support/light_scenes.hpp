#pragma once
// The scenes of the lights study, shared by the tests (tests/render/test_light_render.cpp) and
// the error table (bench/lights.cpp): a plane and a sphere lit by one light of each type, and
// the measured difference between the real-time shading and the reference.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "ibl/bake/bake.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/render/light_sampling.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/shared/light_units.h"

namespace ibl::test {

// A square of side 2 halfSize in the plane y = height, facing +Y.
inline Mesh planeMesh(float halfSize, float height = 0.0f) {
  Mesh m;
  m.positions = {{-halfSize, height, -halfSize},
                 {halfSize, height, -halfSize},
                 {halfSize, height, halfSize},
                 {-halfSize, height, halfSize}};
  m.normals.assign(4, glm::vec3(0, 1, 0));
  m.indices = {0, 2, 1, 0, 3, 2};
  return m;
}

// An IES profile's text (LM-63-2002, type C, absolute photometry) that varies with both angles
// (cos^2 of 0.7 x the vertical, dark above 120 degrees; asymmetric in the horizontal), so that a
// horizontal angle read the wrong way round shows.
inline std::string asymmetricIesText() {
  std::string text =
      "IESNA:LM-63-2002\n[TEST] asymmetric\nTILT=NONE\n1 -1 1 19 13 1 2 0 0 0\n1 1 100\n";
  for (int v = 0; v <= 180; v += 10) text += std::to_string(v) + " ";
  text += "\n";
  for (int h = 0; h <= 360; h += 30) text += std::to_string(h) + " ";
  text += "\n";
  for (int h = 0; h <= 360; h += 30) {
    for (int v = 0; v <= 180; v += 10) {
      const double vr = glm::radians(static_cast<double>(v)),
                   hr = glm::radians(static_cast<double>(h));
      const double cd = v > 120 ? 0.0
                                : 500.0 * std::pow(std::cos(0.7 * vr), 2) *
                                      (1.2 + 0.6 * std::cos(hr) + 0.5 * std::sin(hr));
      text += std::to_string(cd) + " ";
    }
    text += "\n";
  }
  return text;
}

// The bake of a black environment: the lights alone (what --env none does).
struct BlackBake {
  BakeOptions options;
  BakeResult result;
};
inline BlackBake blackBake() {
  BlackBake b;
  Environment black;
  black.equirect = Image(64, 32);
  b.options.specular.size = 16;
  b.options.irradianceSize = 8;
  b.options.dfgSize = 64;
  b.options.dfgSamples = 1024;
  b.result = bakeEnvironment(black, b.options);
  return b;
}

// An orthographic camera looking straight down at `center`, `width` wide, n x n pixels.
inline Camera topDownCamera(glm::vec3 center, float width, int n) {
  Camera c;
  c.perspective = false;
  c.orthoWidth = width;
  c.from = center + glm::vec3(0, 10, 0);
  c.at = center;
  c.up = glm::vec3(0, 0, -1);
  c.width = c.height = n;
  return c;
}

// One light of each type about 1 to 1.5 m above the origin, sized to make its area matter.
inline Light studyLight(LightType type) {
  Light l;
  l.type = type;
  l.name = "study light";
  switch (type) {
    case LightType::Point:
      l.position = {0.3f, 1.5f, 0.2f};
      l.intensity = shared::pointIntensityFromPower(1000.0f);
      break;
    case LightType::Spot:
      l.position = {0.0f, 1.5f, 0.0f};
      l.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.0f));
      l.innerAngle = 0.35f;
      l.outerAngle = 0.7f;
      l.intensity = 300.0f;
      break;
    case LightType::Sun:
      l.direction = glm::normalize(glm::vec3(0.5f, 1.0f, 0.3f));
      l.intensity = 100.0f;
      break;
    case LightType::Sphere:
      l.position = {0.3f, 1.2f, 0.2f};
      l.radius = 0.3f;
      l.intensity = 1000.0f;
      break;
    case LightType::Disk:
      l.position = {0.0f, 1.2f, 0.0f};
      l.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
      l.radius = 0.5f;
      l.intensity = 300.0f;
      break;
    case LightType::Tube:
      l.position = {0.0f, 1.0f, 0.0f};
      l.direction = glm::normalize(glm::vec3(1.0f, 0.0f, 0.3f));
      l.length = 1.5f;
      l.radius = 0.1f;
      l.intensity = 1000.0f;
      break;
    case LightType::Rect:
      l.position = {0.0f, 1.2f, 0.0f};
      l.direction = glm::normalize(glm::vec3(0.0f, -1.0f, 0.2f));
      l.up = glm::normalize(glm::cross(l.direction, glm::vec3(1, 0, 0)));
      l.width = 1.2f;
      l.height = 0.6f;
      l.intensity = 300.0f;
      break;
  }
  checkLight(l);
  return l;
}

enum class StudyShape { Plane, Sphere };

// The study's scene: a 6 x 6 m plane at y = 0, or a sphere of radius 0.5 at (0, 0.1, 0), of one
// material, lit by `light`.
inline Scene studyScene(StudyShape shape, const Light& light, const Material& material) {
  Scene s;
  s.materials = {material};
  if (shape == StudyShape::Plane)
    s.meshes.push_back(planeMesh(3.0f));
  else
    s.spheres.push_back({glm::vec3(0.0f, 0.1f, 0.0f), 0.5f, 0});
  s.lights = {light};
  return s;
}

// Orthographic views from above the horizon and below the lights: the plane from 30 degrees
// up, where the lights' mirror images fall on it; the sphere from the side (+Z).
inline Camera studyCamera(StudyShape shape, int n) {
  Camera c;
  c.perspective = false;
  c.width = c.height = n;
  if (shape == StudyShape::Plane) {
    c.orthoWidth = 3.0f;
    c.at = glm::vec3(0.0f, 0.0f, 0.6f);
    c.from = c.at + 10.0f * glm::vec3(0.0f, 0.5f, 0.8660254f);
  } else {
    c.orthoWidth = 1.1f;
    c.at = glm::vec3(0.0f, 0.1f, 0.0f);
    c.from = c.at + glm::vec3(0.0f, 0.0f, 10.0f);
  }
  return c;
}

struct ApproximationError {
  double relative = 0.0;    // sum |real time - reference| / sum reference, over lit pixels
  double noiseFloor = 0.0;  // the same between two references of different seeds
  double meanRatio = 0.0;   // sum real time / sum reference
};

// Renders the scene both ways (the reference at `spp`, the real-time shading at as many pixel
// positions, up to 256, once per area-light model in `models`) and compares the pixels that see
// the model and not the light (rays through the pixel's corners and center), lit by at least
// 1/1000 of the brightest. One error per model, in order.
inline std::vector<ApproximationError> measureApproximations(
    const Scene& scene, const Camera& camera, const BlackBake& bake, RenderOptions options, int spp,
    const std::vector<AreaLightModel>& models) {
  options.environmentLight = false;
  options.backgroundEnvironment = false;
  options.mode = RenderMode::Reference;
  options.spp = spp;
  const RenderResult ref = renderScene(scene, camera, bake.result, bake.options, options);
  options.seed = 2;
  const RenderResult ref2 = renderScene(scene, camera, bake.result, bake.options, options);
  const auto luminanceOf = [](glm::vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; };
  double peak = 0.0;
  for (const glm::vec3& c : ref.color.pixels) peak = std::max(peak, luminanceOf(c));
  // The pixels compared: covered both ways, lit, not seeing the light.
  std::vector<std::size_t> compared;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * camera.width + x;
      if (ref.alpha[i] < 1.0f || luminanceOf(ref.color.pixels[i]) < 1e-3 * peak) continue;
      bool seesLight = false;
      for (glm::vec2 o : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1), glm::vec2(1, 1),
                          glm::vec2(0.5f, 0.5f)}) {
        const Ray r = camera.generateRay(static_cast<float>(x) + o.x, static_cast<float>(y) + o.y);
        for (const Light& l : scene.lights)
          seesLight = seesLight || intersectLight(l, r.origin, r.direction);
      }
      if (!seesLight) compared.push_back(i);
    }
  std::vector<ApproximationError> errors;
  options.mode = RenderMode::SplitSum;
  options.spp = std::min(spp, 256);  // as many pixel positions: sharp highlights alias alike
  options.seed = 1;
  for (AreaLightModel model : models) {
    options.areaLights = model;
    const RenderResult fast = renderScene(scene, camera, bake.result, bake.options, options);
    double diff = 0.0, noise = 0.0, sumRef = 0.0, sumFast = 0.0;
    for (std::size_t i : compared) {
      if (fast.alpha[i] < 1.0f) continue;
      const double a = luminanceOf(fast.color.pixels[i]), b = luminanceOf(ref.color.pixels[i]),
                   b2 = luminanceOf(ref2.color.pixels[i]);
      diff += std::abs(a - b);
      noise += std::abs(b2 - b);
      sumRef += b;
      sumFast += a;
    }
    ApproximationError e;
    if (sumRef > 0.0) {
      e.relative = diff / sumRef;
      e.noiseFloor = noise / sumRef;
      e.meanRatio = sumFast / sumRef;
    }
    errors.push_back(e);
  }
  return errors;
}

// The same for the options' own area-light model.
inline ApproximationError measureApproximation(const Scene& scene, const Camera& camera,
                                               const BlackBake& bake, const RenderOptions& options,
                                               int spp) {
  return measureApproximations(scene, camera, bake, options, spp, {options.areaLights})[0];
}

}  // namespace ibl::test
