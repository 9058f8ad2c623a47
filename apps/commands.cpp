#include "commands.hpp"

#include <cmath>
#include <cstdio>

#include <fmt/core.h>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/core/stats.hpp"
#include "ibl/env/default_environment.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/env/sun_extraction.hpp"
#include "ibl/gpu/compute.hpp"

namespace ibl::cli {

void warnAboutReplacedPixels(std::string_view name, const InvalidPixelCounts& replaced,
                             const GlobalOptions& global) {
  if (replaced.total() == 0 || global.quiet) return;
  // Small negative values are common (lossy EXR compression, denoisers, color-space
  // conversions) and harmless once read as 0: a note. NaN and infinities are damage: a warning.
  if (replaced.nan == 0 && replaced.infinite == 0) {
    fmt::print(stderr, "ibl: note: {}: {} negative pixel components read as 0\n", name,
               replaced.negative);
    return;
  }
  fmt::print(stderr,
             "ibl: warning: {}: replaced {} NaN, {} infinite and {} negative pixel components by "
             "0\n",
             name, replaced.nan, replaced.infinite, replaced.negative);
}

const CLI::Validator& finiteNumber() {
  static const CLI::Validator validator(
      [](const std::string& text) -> std::string {
        double value = 0.0;
        try {
          value = std::stod(text);
        } catch (const std::exception&) {
          return {};  // not a number at all: the option's own conversion reports it
        }
        return std::isfinite(value) ? std::string() : "'" + text + "' is not a finite number";
      },
      "FINITE");
  return validator;
}

void requireLight(const Environment& env, std::string_view name) {
  if (!brightestDirection(env))
    fail(std::string(name),
         "holds no light: every pixel is zero, NaN, infinite or negative after loading");
}

std::unique_ptr<gpu::Context> openDevice(const std::string& choice) {
  if (choice == "cpu") return nullptr;
  if (choice == "auto") {
    bool realGpu = false;
    for (const auto& d : gpu::listDevices()) realGpu |= d.type != "cpu";
    if (!realGpu) return nullptr;
  }
  return gpu::Context::create();
}

Image skyImage(const SkyParameters& p, int width, int height, bool paintSun, gpu::Context* device) {
  return device ? gpu::skyPanorama(*device, p, width, height, paintSun)
                : SkyModel(p).panorama(width, height, paintSun);
}

SourceEnvironment loadSourceEnvironment(const std::string& input, const LoadOptions& options,
                                        bool removeSun, const GlobalOptions& global,
                                        gpu::Context* device) {
  SourceEnvironment s;
  if (isSkySpec(input)) {
    if (removeSun)
      fail("--extract-sun", fmt::format("contradicts {}: a sky's sun is a light already", input));
    const SkySpec spec = parseSkySpec(input);
    s.name = input;
    s.loaded.format = "sky";
    s.loaded.environment.layout = Layout::Equirect;
    s.loaded.environment.equirect =
        skyImage(spec.parameters, spec.width, spec.height, false, device);
    const Light sun = skySun(spec.parameters);
    const SkyParameters& p = spec.parameters;
    nlohmann::json records = {{"sky",
                               {{"description", input},
                                {"sun_elevation", p.sunElevation},
                                {"sun_azimuth", p.sunAzimuth},
                                {"altitude", p.altitude},
                                {"turbidity", p.turbidity},
                                {"ozone", p.ozone},
                                {"ground_albedo", p.groundAlbedo}}},
                              {"lights", nlohmann::json::array()}};
    if (sun.intensity > 0.0f) {
      s.lights.push_back(sun);
      records["lights"].push_back(nlohmann::json::parse(sunLightJson(sun)));
    }
    s.manifestRecords = records.dump();
    return s;
  }
  s.name = input.empty() ? std::string(kDefaultEnvironmentName) + " (bundled)" : input;
  s.loaded = input.empty() ? loadEnvironmentFromMemory(defaultEnvironmentBytes(), s.name, options)
                           : loadEnvironment(input, options);
  if (!input.empty()) warnAboutReplacedPixels(s.name, s.loaded.replaced, global);
  if (!removeSun) return s;
  Environment& env = s.loaded.environment;
  if (env.layout != Layout::Equirect) {
    // Found and filled on a panorama of the cube's resolution (4 n wide).
    if (env.isCube()) env.equirect = flatFromCube(env.cube, 0, Layout::Equirect);
    env.layout = Layout::Equirect;
    env.cube = CubeMap();
  }
  const auto sun = extractSun(env.equirect);
  if (!sun)
    fail(s.name,
         "--extract-sun: no compact bright source (the brightest pixel is not 50 times "
         "its surroundings, or it spans more than 20 degrees)");
  Light light = sun->light;
  light.name = fmt::format("{}: extracted sun", s.name);
  s.lights.push_back(light);
  nlohmann::json records;
  records["lights"] = nlohmann::json::array({nlohmann::json::parse(sunLightJson(light))});
  records["extracted_sun"] = {{"pixels", sun->pixels}, {"peak_over_surroundings", sun->peakRatio}};
  s.manifestRecords = records.dump();
  if (!global.quiet)
    fmt::print(stderr,
               "ibl: note: {}: extracted the sun ({:.4g} lx, {:.2f} degrees across, direction "
               "{:.4f},{:.4f},{:.4f}; {} pixels filled)\n",
               s.name, light.intensity, glm::degrees(light.angularDiameter), light.direction.x,
               light.direction.y, light.direction.z, sun->pixels);
  return s;
}

}  // namespace ibl::cli
