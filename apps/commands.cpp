#include "commands.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>

#include <fmt/core.h>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/core/stats.hpp"
#include "ibl/env/default_environment.hpp"
#include "ibl/env/photometry.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/env/sun_extraction.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/io/image_io.hpp"

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

std::string damageSummary(const PixelDamage& damage, bool cube) {
  if (damage.empty()) return "no pixel";
  const std::size_t regions = damage.regions.size();
  std::string places;
  for (std::size_t i = 0; i < std::min<std::size_t>(regions, 3); ++i) {
    const DamagedRegion& r = damage.regions[i];
    const auto span = [](int a, int b) {
      return a == b ? fmt::format("{}", a) : fmt::format("{}-{}", a, b);
    };
    places +=
        fmt::format("{}{}x {}, y {}", i ? "; " : "",
                    cube ? fmt::format("face {}: ", kFaceNames[static_cast<std::size_t>(r.face)])
                         : std::string(),
                    span(r.x0, r.x1), span(r.y0, r.y1));
  }
  return fmt::format("{} pixel{} in {} region{} ({}{})", damage.pixels(),
                     damage.pixels() == 1 ? "" : "s", regions, regions == 1 ? "" : "s", places,
                     regions > 3 ? "; ..." : "");
}

void reportLoadedPixels(std::string_view name, const LoadedEnvironment& loaded,
                        const GlobalOptions& global) {
  if (!global.quiet && loaded.repair)
    fmt::print(stderr,
               "ibl: note: {}: repaired {} from their neighbourhood; the environment's power "
               "(luminance over the sphere) changed by {:+.3g} %\n",
               name, damageSummary(loaded.damage, loaded.environment.isCube()),
               100.0 * loaded.repair->powerChange());
  else if (!global.quiet && !loaded.damage.empty())
    fmt::print(stderr,
               "ibl: warning: {}: {} damaged: channels that contradict their neighbourhood by "
               "orders of magnitude, or negative beyond a codec's ringing (lossy compression?); "
               "`ibl convert --repair-damage` "
               "replaces them\n",
               name, damageSummary(loaded.damage, loaded.environment.isCube()));
  warnAboutReplacedPixels(name, loaded.replaced, global);
}

namespace {

// The option's text as a number, or nothing when it is not one (the option's own conversion
// then reports it).
std::optional<double> numberOf(const std::string& text) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used != text.size()) return std::nullopt;
    return value;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// A validator from a rule that returns the problem ("" when the value is right).
CLI::Validator numberRule(std::string description, std::function<std::string(double)> rule) {
  return CLI::Validator(
      [rule = std::move(rule)](std::string& text) -> std::string {
        const std::optional<double> value = numberOf(text);
        if (!value) return {};
        if (!std::isfinite(*value)) return "'" + text + "' is not a finite number";
        const std::string problem = rule(*value);
        return problem.empty() ? problem : problem + ", not " + text;
      },
      std::move(description));
}

}  // namespace

std::vector<float> parseNumbers(const std::string& text, std::size_t count, const char* option) {
  std::vector<float> v;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, end - begin);
    const std::optional<double> x = numberOf(item);
    if (!x) failUsage(option, fmt::format("'{}' is not a number", item));
    if (!std::isfinite(*x) || std::abs(*x) > 3.4e38)
      failUsage(option, fmt::format("'{}' is not finite", text));
    v.push_back(static_cast<float>(*x));
    begin = end + 1;
  }
  if (v.size() != count)
    failUsage(option, fmt::format("expected {} comma-separated numbers, got '{}'", count, text));
  return v;
}

Shard parseShard(const std::string& text) {
  // K, a slash, N: digits only (from_chars takes no '+' or spaces, and reports overflow).
  const char* const end = text.data() + text.size();
  int k = -1, n = 0;
  const auto first = std::from_chars(text.data(), end, k);
  const bool ok = first.ec == std::errc() && first.ptr != end && *first.ptr == '/' && [&] {
    const auto second = std::from_chars(first.ptr + 1, end, n);
    return second.ec == std::errc() && second.ptr == end;
  }();
  if (!ok || n < 1 || k < 0 || k >= n)
    failUsage("--shard", fmt::format("'{}': expected K/N with 0 <= K < N", text));
  return {k, n};
}

std::string formatNumber(double value) {
  if (value == std::floor(value) && std::abs(value) < 1e15)
    return fmt::format("{}", static_cast<long long>(value));
  return fmt::format("{:.6g}", value);
}

const CLI::Validator& finiteNumber() {
  static const CLI::Validator validator = numberRule("FINITE", [](double) { return ""; });
  return validator;
}

CLI::Validator numberIn(double lo, double hi) {
  const std::string range = formatNumber(lo) + " to " + formatNumber(hi);
  return numberRule(range, [lo, hi, range](double v) {
    return v >= lo && v <= hi ? std::string() : "must be from " + range;
  });
}

CLI::Validator positiveNumber() {
  return numberRule("POSITIVE", [](double v) { return v > 0.0 ? "" : "must be positive"; });
}

CLI::Validator nonNegativeNumber() {
  return numberRule("NON-NEGATIVE", [](double v) { return v >= 0.0 ? "" : "must be 0 or more"; });
}

CLI::Validator powerOfTwo(int lo, int hi) {
  const std::string range =
      fmt::format("a power of two from {} to {}", formatNumber(lo), formatNumber(hi));
  return numberRule(range, [lo, hi, range](double v) {
    const bool ok =
        v >= lo && v <= hi && v == std::floor(v) && std::has_single_bit(static_cast<unsigned>(v));
    return ok ? std::string() : "must be " + range;
  });
}

void requireLight(const Environment& env, std::string_view name) {
  if (!brightestDirection(env))
    fail(std::string(name),
         "holds no light: every pixel is zero, NaN, infinite or negative after loading");
}

gpu::ComputeDevice deviceChoice(const std::string& text) {
  const std::optional<gpu::ComputeDevice> choice = gpu::parseComputeDevice(text);
  if (!choice) failUsage("--device", fmt::format("'{}' is not cpu, gpu or auto", text));
  return *choice;
}

SourceEnvironment loadSourceEnvironment(const std::string& input, const LoadOptions& options,
                                        bool removeSun, const GlobalOptions& global,
                                        gpu::Context* device) {
  SourceEnvironment s;
  if (isSkySpec(input)) {
    if (removeSun)
      failUsage("--extract-sun",
                fmt::format("contradicts {}: a sky's sun is a light already", input));
    const SkySpec spec = parseSkySpec(input);
    s.name = input;
    s.loaded.format = "sky";
    s.loaded.environment.layout = Layout::Equirect;
    s.loaded.environment.equirect =
        gpu::skyPanoramaOn(device, spec.parameters, spec.width, spec.height, false);
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
      records["lights"].push_back(nlohmann::json::parse(lightJson(sun)));
    }
    s.manifestRecords = records.dump();
    return s;
  }
  s.name = input.empty() ? std::string(kDefaultEnvironmentName) + " (bundled)" : input;
  s.loaded = input.empty() ? loadEnvironmentFromMemory(defaultEnvironmentBytes(), s.name, options)
                           : loadEnvironment(input, options);
  if (!input.empty()) reportLoadedPixels(s.name, s.loaded, global);
  if (removeSun) extractSourceSun(s, global);
  return s;
}

SourceEnvironment sourceFromImage(Image image, const std::string& name, const LoadOptions& options,
                                  bool removeSun, const GlobalOptions& global) {
  SourceEnvironment s;
  s.name = name;
  DecodedFile file;
  file.format = FileFormat::Exr;  // linear radiance
  file.levels = {{std::move(image)}};
  s.loaded = loadEnvironment(std::move(file), s.name, options);
  s.loaded.format = "array";
  reportLoadedPixels(s.name, s.loaded, global);
  if (removeSun) extractSourceSun(s, global);
  return s;
}

void extractSourceSun(SourceEnvironment& s, const GlobalOptions& global) {
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
  records["lights"] = nlohmann::json::array({nlohmann::json::parse(lightJson(light))});
  records["extracted_sun"] = {{"pixels", sun->pixels}, {"peak_over_surroundings", sun->peakRatio}};
  s.manifestRecords = records.dump();
  if (!global.quiet)
    fmt::print(stderr,
               "ibl: note: {}: extracted the sun ({:.4g} lx, {:.2f} degrees across, direction "
               "{:.4f},{:.4f},{:.4f}; {} pixels filled)\n",
               s.name, light.intensity, glm::degrees(light.angularDiameter), light.direction.x,
               light.direction.y, light.direction.z, sun->pixels);
}

void addEnvScaleOptions(CLI::App* cmd, EnvScaleOptions& o) {
  cmd->add_option("--env-intensity", o.intensity,
                  "Multiply the environment (and the sun it brings) by K before anything else, "
                  "e.g. to bring an HDRI in relative units to nits")
      ->check(positiveNumber());
  cmd->add_option("--env-illuminance", o.illuminance,
                  "Scale the environment (and the sun it brings) so that it lights an upward "
                  "horizontal surface with LUX lux, the sun included (e.g. 1000 overcast, "
                  "100000 midday sun); recorded in the manifest")
      ->check(positiveNumber());
}

void checkEnvScaleOptions(const EnvScaleOptions& o, const std::string& nothingToScale) {
  if (o.intensity && o.illuminance)
    failUsage("--env-illuminance",
              fmt::format("contradicts --env-intensity {}: --env-illuminance {} sets the factor "
                          "itself; pass one of them",
                          formatNumber(*o.intensity), formatNumber(*o.illuminance)));
  if (o.given() && !nothingToScale.empty())
    failUsage(o.intensity ? "--env-intensity" : "--env-illuminance",
              fmt::format("contradicts {}: there is no environment to scale", nothingToScale));
}

std::string EnvScale::recordJson() const {
  if (option.empty()) return {};
  nlohmann::ordered_json j;
  j["option"] = option;
  j["factor"] = factor;
  if (option == "--env-illuminance") j["target_lux"] = targetLux;
  j["measured_lux"] = measuredLux;
  j["scaled_lux"] = measuredLux * factor;
  return j.dump();
}

EnvScale envScaleFor(const EnvScaleOptions& o, double measuredLux, std::string_view name) {
  EnvScale scale;
  scale.measuredLux = measuredLux;
  if (o.intensity) {
    scale.option = "--env-intensity";
    scale.factor = *o.intensity;
  } else if (o.illuminance) {
    scale.option = "--env-illuminance";
    scale.targetLux = *o.illuminance;
    scale.factor =
        illuminanceScale(measuredLux, *o.illuminance, fmt::format("{}: --env-illuminance", name));
  }
  return scale;
}

EnvScale scaleSourceEnvironment(SourceEnvironment& s, const EnvScaleOptions& o,
                                const GlobalOptions& global) {
  if (!o.given()) return {};
  Environment& env = s.loaded.environment;
  const EnvScale scale = envScaleFor(o, horizontalIlluminance(env, s.lights), s.name);
  scaleEnvironment(env, scale.factor, fmt::format("{}: {}", s.name, scale.option));
  for (Light& light : s.lights) light.intensity *= static_cast<float>(scale.factor);
  nlohmann::json records = s.manifestRecords.empty() ? nlohmann::json::object()
                                                     : nlohmann::json::parse(s.manifestRecords);
  if (records.contains("lights")) {
    records["lights"] = nlohmann::json::array();
    for (const Light& light : s.lights)
      records["lights"].push_back(nlohmann::json::parse(lightJson(light)));
  }
  records["environment_scale"] = nlohmann::json::parse(scale.recordJson());
  s.manifestRecords = records.dump();
  if (!global.quiet)
    fmt::print(stderr,
               "ibl: note: {}: scaled by {:.6g} ({}: {:.6g} lx -> {:.6g} lx on an upward "
               "surface{})\n",
               s.name, scale.factor, scale.option, scale.measuredLux,
               scale.measuredLux * scale.factor, s.lights.empty() ? "" : ", the sun included");
  return scale;
}

}  // namespace ibl::cli
