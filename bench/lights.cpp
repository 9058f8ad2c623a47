// The error of each real-time light approximation against the reference renderer (the table in
// docs/lights.md): every light type over a plane and a sphere, roughness 0.1 to 1, a gray
// dielectric and a metal, multiple-scattering compensation off (the reference has none). Also
// the CPU cost of each light per shaded pixel. Area lights: Frostbite's approximations and LTCs.
// Usage: ibl_lights [reference spp, default 1024] [any second argument: the table alone]
#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "support/light_scenes.hpp"

using namespace ibl;
using namespace ibl::test;

int main(int argc, char** argv) {
  const int spp = argc > 1 ? std::atoi(argv[1]) : 1024;
  const BlackBake bake = blackBake();
  const LightType types[] = {LightType::Point, LightType::Spot, LightType::Sun, LightType::Sphere,
                             LightType::Disk,  LightType::Tube, LightType::Rect};
  const float roughnesses[] = {0.1f, 0.25f, 0.5f, 0.75f, 1.0f};
  RenderOptions options;
  options.multipleScattering = MultipleScattering::Off;
  for (int metal = 0; metal < 2; ++metal) {
    Material m;
    m.baseColor = glm::vec3(metal ? 0.9f : 0.5f);
    m.metallic = metal ? 1.0f : 0.0f;
    fmt::print(
        "\n{} (base color {}), reference {} spp; mean |real time - reference| / mean "
        "reference, plane / sphere (noise floor of the reference in brackets)\n",
        metal ? "metal" : "dielectric", m.baseColor.x, spp);
    fmt::print("| light |");
    for (float r : roughnesses) fmt::print(" r = {} |", r);
    fmt::print("\n| --- |");
    for (std::size_t k = 0; k < std::size(roughnesses); ++k) fmt::print(" --- |");
    fmt::print("\n");
    for (LightType type : types) {
      // Area lights: Frostbite's approximations and LTCs against the same reference.
      const bool area = type >= LightType::Sphere;
      std::vector<std::string> rows = {area ? std::string(lightTypeName(type)) + ", frostbite"
                                            : std::string(lightTypeName(type))};
      if (area) rows.push_back(std::string(lightTypeName(type)) + ", ltc");
      for (std::string& row : rows) row = "| " + row + " |";
      for (float r : roughnesses) {
        m.roughness = r;
        const Light light = studyLight(type);
        const std::vector<AreaLightModel> models =
            area ? std::vector<AreaLightModel>{AreaLightModel::Frostbite, AreaLightModel::Ltc}
                 : std::vector<AreaLightModel>{AreaLightModel::Ltc};
        const auto plane =
            measureApproximations(studyScene(StudyShape::Plane, light, m),
                                  studyCamera(StudyShape::Plane, 64), bake, options, spp, models);
        const auto sphere =
            measureApproximations(studyScene(StudyShape::Sphere, light, m),
                                  studyCamera(StudyShape::Sphere, 64), bake, options, spp, models);
        for (std::size_t k = 0; k < rows.size(); ++k)
          rows[k] += fmt::format(" {:.1f} / {:.1f} % ({:.1f}) |", 100.0 * plane[k].relative,
                                 100.0 * sphere[k].relative,
                                 100.0 * std::max(plane[k].noiseFloor, sphere[k].noiseFloor));
      }
      for (const std::string& row : rows) fmt::print("{}\n", row);
    }
  }
  if (argc > 2) return 0;  // the table alone
  // Cost: a 512^2 plane, split sum, one light of each type, minus the cost without lights.
  fmt::print("\nCPU cost of one light per shaded pixel (512^2 plane, split sum, 1 spp)\n");
  Material m;
  m.roughness = 0.5f;
  options.spp = 1;
  options.environmentLight = false;
  const auto timeOf = [&](const Scene& s) {
    double best = 1e30;
    for (int k = 0; k < 5; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      renderScene(s, topDownCamera(glm::vec3(0.0f), 4.0f, 512), bake.result, bake.options, options);
      best = std::min(
          best,
          std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count());
    }
    return best;
  };
  Scene none = studyScene(StudyShape::Plane, studyLight(LightType::Point), m);
  none.lights.clear();
  const double base = timeOf(none);
  for (LightType type : types)
    for (AreaLightModel model : {AreaLightModel::Frostbite, AreaLightModel::Ltc}) {
      if (model == AreaLightModel::Ltc && type < LightType::Sphere) continue;
      options.areaLights = model;
      Scene s = studyScene(StudyShape::Plane, studyLight(type), m);
      s.lights.assign(16, s.lights[0]);
      fmt::print("| {}{} | {:.0f} ns |\n", lightTypeName(type),
                 type < LightType::Sphere       ? ""
                 : model == AreaLightModel::Ltc ? ", ltc"
                                                : ", frostbite",
                 (timeOf(s) - base) / (16.0 * 512 * 512));
    }
  return 0;
}
