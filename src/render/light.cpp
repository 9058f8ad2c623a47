#include "ibl/render/light.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/json_file.hpp"
#include "ibl/math/color.hpp"
#include "ibl/shared/light_units.h"

namespace ibl {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

using Json = nlohmann::json;

// The fields each type accepts beyond the common ones (type, intensity, unit, color, kelvin,
// range).
const std::map<std::string, std::set<std::string>, std::less<>>& typeFields() {
  static const std::map<std::string, std::set<std::string>, std::less<>> fields = {
      {"point", {"position", "ies", "radius"}},
      {"spot", {"position", "direction", "inner_angle", "outer_angle", "ies"}},
      {"sun", {"direction", "angular_diameter"}},
      {"sphere", {"position", "radius"}},
      {"disk", {"position", "direction", "radius"}},
      {"tube", {"position", "axis", "length", "radius"}},
      {"rect", {"position", "direction", "up", "width", "height"}},
  };
  return fields;
}

// Reads one light's fields, each error naming the light.
class LightReader {
 public:
  LightReader(const Json& j, std::string name) : j_(j), name_(std::move(name)) {}

  [[noreturn]] void error(std::string_view problem) const { fail(name_, problem); }

  bool has(const char* key) const { return j_.contains(key); }

  float number(const char* key) const {
    if (!has(key)) error(fmt::format("missing \"{}\"", key));
    const Json& v = j_.at(key);
    if (!v.is_number()) error(fmt::format("\"{}\" must be a number", key));
    const double d = v.get<double>();
    if (!std::isfinite(d) || std::abs(d) > 1e30)
      error(fmt::format("\"{}\" must be a finite number", key));
    return static_cast<float>(d);
  }
  float positive(const char* key) const {
    const float v = number(key);
    if (!(v > 0.0f)) error(fmt::format("\"{}\" must be positive, not {}", key, v));
    return v;
  }
  glm::vec3 vec3(const char* key) const {
    if (!has(key)) error(fmt::format("missing \"{}\"", key));
    const Json& v = j_.at(key);
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() ||
        !v[2].is_number())
      error(fmt::format("\"{}\" must be an array of three numbers", key));
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
      const double d = v[static_cast<std::size_t>(i)].get<double>();
      if (!std::isfinite(d) || std::abs(d) > 1e8)
        error(fmt::format("\"{}\" must be finite (at most 1e8 per coordinate)", key));
      out[i] = static_cast<float>(d);
    }
    return out;
  }
  glm::vec3 unitVector(const char* key) const {
    const glm::vec3 v = vec3(key);
    if (glm::length(v) < 1e-6f) error(fmt::format("\"{}\" must not be the zero vector", key));
    return glm::normalize(v);
  }
  std::string string(const char* key) const {
    if (!has(key)) error(fmt::format("missing \"{}\"", key));
    if (!j_.at(key).is_string()) error(fmt::format("\"{}\" must be a string", key));
    return j_.at(key).get<std::string>();
  }
  const Json& json(const char* key) const { return j_.at(key); }

 private:
  const Json& j_;
  std::string name_;
};

// The intensity field in the light's own unit: cd for punctual lights (lumens converted),
// lx for the sun, nit for area lights (lumens converted by the shape's area).
void readIntensity(const LightReader& r, const std::string& unit, Light& light,
                   SpotLumens spotLumens) {
  const float value = r.number("intensity");
  if (value < 0.0f) r.error(fmt::format("\"intensity\" must not be negative, not {}", value));
  const auto allow = [&](std::initializer_list<const char*> units) {
    for (const char* u : units)
      if (unit == u) return;
    std::string list;
    for (const char* u : units) list += (list.empty() ? "\"" : " or \"") + std::string(u) + "\"";
    r.error(fmt::format("unit \"{}\" is not one of {}", unit, list));
  };
  switch (light.type) {
    case LightType::Point:
      allow({"cd", "lm"});
      light.intensity = unit == "lm" ? shared::pointIntensityFromPower(value) : value;
      break;
    case LightType::Spot:
      allow({"cd", "lm"});
      light.intensity = unit == "lm"
                            ? shared::spotIntensityFromPower(value, std::cos(light.outerAngle),
                                                             spotLumens == SpotLumens::Physical)
                            : value;
      break;
    case LightType::Sun:
      allow({"lux"});
      light.intensity = value;
      break;
    default:
      allow({"nit", "lm"});
      if (unit == "nit") {
        light.intensity = value;
      } else if (light.type == LightType::Sphere) {
        light.intensity = shared::sphereLuminanceFromPower(value, light.radius);
      } else if (light.type == LightType::Disk) {
        light.intensity = shared::diskLuminanceFromPower(value, light.radius);
      } else if (light.type == LightType::Tube) {
        light.intensity = shared::tubeLuminanceFromPower(value, light.radius, light.length);
      } else {
        light.intensity = shared::rectLuminanceFromPower(value, light.width, light.height);
      }
  }
}

// "ies": "file.ies" takes the profile's shape, scaled so that its peak is the light's intensity
// (cd) or its flux the light's power (lm); "ies": {"file": "file.ies", "multiplier": m} takes
// the file's candela times m, and then the light has no intensity or unit of its own.
void attachIesProfile(const LightReader& r, const std::filesystem::path& baseDirectory,
                      Light& light, const std::string& unit, float value) {
  const Json& j = r.json("ies");
  std::filesystem::path file;
  float multiplier = 1.0f;
  const bool absolute = j.is_object();
  if (j.is_string()) {
    file = j.get<std::string>();
  } else if (absolute) {
    for (const auto& [key, v] : j.items())
      if (key != "file" && key != "multiplier")
        r.error(fmt::format("\"ies\" has an unknown field \"{}\"", key));
    if (!j.contains("file") || !j["file"].is_string())
      r.error("\"ies\" must have a \"file\" string");
    file = j["file"].get<std::string>();
    if (j.contains("multiplier")) {
      if (!j["multiplier"].is_number() || !std::isfinite(j["multiplier"].get<double>()) ||
          j["multiplier"].get<double>() < 0.0)
        r.error("\"ies\".\"multiplier\" must be a finite number >= 0");
      multiplier = j["multiplier"].get<float>();
    }
  } else {
    r.error("\"ies\" must be a file name or {\"file\": ..., \"multiplier\": ...}");
  }
  if (file.is_relative()) file = baseDirectory / file;
  auto profile = std::make_shared<IesProfile>(readIes(file));
  light.iesFile = std::filesystem::absolute(file);
  if (absolute) {
    light.iesScale = multiplier;
  } else if (unit == "lm") {
    const double flux = profile->flux();
    if (!(flux > 0.0)) r.error(fmt::format("{}: the profile emits no light", file.string()));
    light.iesScale = static_cast<float>(value / flux);
  } else {
    const float peak = profile->maxCandela();
    if (!(peak > 0.0f)) r.error(fmt::format("{}: the profile emits no light", file.string()));
    light.iesScale = value / peak;
  }
  light.ies = std::move(profile);
}

Light readLight(const Json& j, const std::string& name, const std::filesystem::path& baseDirectory,
                SpotLumens spotLumens) {
  if (!j.is_object()) fail(name, "must be a JSON object");
  if (!j.contains("type") || !j["type"].is_string()) fail(name, "missing \"type\"");
  const std::string type = j["type"].get<std::string>();
  const auto fields = typeFields().find(type);
  if (fields == typeFields().end())
    fail(name,
         fmt::format("unknown type \"{}\" (point, spot, sun, sphere, disk, tube or rect)", type));
  const LightReader r(j, fmt::format("{} ({})", name, type));
  static const std::set<std::string> common = {"type",  "intensity", "unit",
                                               "color", "kelvin",    "range"};
  for (const auto& [key, v] : j.items())
    if (!common.contains(key) && !fields->second.contains(key))
      r.error(fmt::format("unknown field \"{}\" for a {} light", key, type));

  Light light;
  light.name = fmt::format("{} ({})", name, type);
  const bool absoluteIes = j.contains("ies") && j["ies"].is_object();
  if (type == "point") {
    light.type = LightType::Point;
    light.position = r.vec3("position");
    if (r.has("radius")) {
      light.radius = r.number("radius");
      if (light.radius < 0.0f) r.error("\"radius\" must not be negative");
      if (light.radius > 0.0f) {
        if (r.has("ies")) r.error("a point light with a radius is a sphere: it takes no \"ies\"");
        light.type = LightType::Sphere;
      }
    }
  } else if (type == "spot") {
    light.type = LightType::Spot;
    light.position = r.vec3("position");
    light.direction = r.unitVector("direction");
    const float inner = r.number("inner_angle"), outer = r.number("outer_angle");
    if (!(inner >= 0.0f && inner <= outer && outer > 0.0f && outer <= 90.0f))
      r.error(
          fmt::format("angles must satisfy 0 <= inner_angle <= outer_angle <= 90 and "
                      "outer_angle > 0 (degrees), got {} and {}",
                      inner, outer));
    light.innerAngle = glm::radians(inner);
    light.outerAngle = glm::radians(outer);
  } else if (type == "sun") {
    light.type = LightType::Sun;
    light.direction = r.unitVector("direction");
    if (r.has("angular_diameter")) {
      const float deg = r.number("angular_diameter");
      if (!(deg > 0.0f && deg <= 30.0f))
        r.error(fmt::format("\"angular_diameter\" must be in (0, 30] degrees, not {}", deg));
      light.angularDiameter = glm::radians(deg);
    }
  } else if (type == "sphere") {
    light.type = LightType::Sphere;
    light.position = r.vec3("position");
    light.radius = r.positive("radius");
  } else if (type == "disk") {
    light.type = LightType::Disk;
    light.position = r.vec3("position");
    light.direction = r.unitVector("direction");
    light.radius = r.positive("radius");
  } else if (type == "tube") {
    light.type = LightType::Tube;
    light.position = r.vec3("position");
    light.direction = r.unitVector("axis");
    light.length = r.number("length");
    if (!(light.length >= 0.0f)) r.error("\"length\" must not be negative");
    light.radius = r.positive("radius");
  } else {
    light.type = LightType::Rect;
    light.position = r.vec3("position");
    light.direction = r.unitVector("direction");
    const glm::vec3 up = r.unitVector("up");
    const glm::vec3 orthogonal = up - glm::dot(up, light.direction) * light.direction;
    if (glm::length(orthogonal) < 1e-3f) r.error("\"up\" is parallel to \"direction\"");
    light.up = glm::normalize(orthogonal);
    light.width = r.positive("width");
    light.height = r.positive("height");
  }
  if (absoluteIes) {
    if (r.has("intensity") || r.has("unit"))
      r.error(
          "an absolute \"ies\" profile ({\"file\": ...}) gives the intensity: no "
          "\"intensity\" or \"unit\"");
  } else {
    readIntensity(r, r.string("unit"), light, spotLumens);
  }
  if (r.has("ies"))
    attachIesProfile(r, baseDirectory, light, absoluteIes ? "" : r.string("unit"),
                     absoluteIes ? 0.0f : r.number("intensity"));
  if (r.has("color") && r.has("kelvin")) r.error("give \"color\" or \"kelvin\", not both");
  if (r.has("color")) {
    light.color = r.vec3("color");
    if (light.color.x < 0.0f || light.color.y < 0.0f || light.color.z < 0.0f)
      r.error("\"color\" must not be negative");
  }
  if (r.has("kelvin")) {
    const float k = r.number("kelvin");
    if (!(k >= 1000.0f && k <= 40000.0f))
      r.error(fmt::format("\"kelvin\" must be in [1000, 40000], not {}", k));
    light.color = blackbodyColor(k);
  }
  if (r.has("range")) {
    light.range = r.number("range");
    if (light.range < 0.0f) r.error("\"range\" must not be negative");
    if (light.type == LightType::Sun) r.error("the sun takes no \"range\"");
  }
  checkLight(light);
  return light;
}

}  // namespace

std::string_view lightTypeName(LightType type) {
  switch (type) {
    case LightType::Point:
      return "point";
    case LightType::Spot:
      return "spot";
    case LightType::Sun:
      return "sun";
    case LightType::Sphere:
      return "sphere";
    case LightType::Disk:
      return "disk";
    case LightType::Tube:
      return "tube";
    case LightType::Rect:
      return "rect";
  }
  return "?";
}

glm::vec3 Light::iesNadir() const {
  return shared::iesNadir(shadingLightOf(*this));
}

glm::vec3 Light::iesHorizontalAxis() const {
  return shared::iesHorizontalAxis(iesNadir());
}

float Light::intensityToward(glm::vec3 w) const {
  if (!ies) return intensity;
  const glm::vec2 angles = shared::iesAngles(iesNadir(), w);
  return iesScale * ies->intensity(angles.x, angles.y);
}

double Light::power() const {
  const double i = intensity * luminance(color);
  switch (type) {
    case LightType::Point:
      return ies ? iesScale * ies->flux() * luminance(color) : 4.0 * kPi * i;
    case LightType::Spot: {
      if (ies) return iesScale * ies->flux() * luminance(color);
      // The smooth falloff between the cones: integrate t^2 over the solid angle.
      const int n = 512;
      double sum = 0.0;
      const double ci = std::cos(innerAngle), co = std::cos(outerAngle);
      for (int k = 0; k < n; ++k) {
        const double c = co + (1.0 - co) * (k + 0.5) / n;
        sum += shared::spotAngleAttenuation(static_cast<float>(c), static_cast<float>(ci),
                                            static_cast<float>(co));
      }
      return i * 2.0 * kPi * (1.0 - co) * sum / n;
    }
    case LightType::Sun:
      return 0.0;
    case LightType::Sphere:
      return i * kPi * 4.0 * kPi * radius * radius;
    case LightType::Disk:
      return i * kPi * kPi * radius * radius;
    case LightType::Tube:
      return i * kPi * (2.0 * kPi * radius * length + 4.0 * kPi * radius * radius);
    case LightType::Rect:
      return i * kPi * width * height;
  }
  return 0.0;
}

void checkLight(const Light& l) {
  const auto finite3 = [](glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
  };
  if (!finite3(l.position) || !finite3(l.direction) || !finite3(l.color) ||
      !std::isfinite(l.intensity) || l.intensity < 0.0f || l.color.x < 0.0f || l.color.y < 0.0f ||
      l.color.z < 0.0f)
    fail(l.name, "position, direction, color and intensity must be finite (and not negative)");
  if (std::abs(glm::length(l.direction) - 1.0f) > 1e-3f) fail(l.name, "direction must be unit");
  if (!(l.range >= 0.0f) || !std::isfinite(l.range)) fail(l.name, "range must be >= 0");
  const auto positive = [&](float v, const char* what) {
    if (!(v > 0.0f) || !std::isfinite(v) || v > 1e8f)
      fail(l.name, fmt::format("{} must be positive and finite, not {}", what, v));
  };
  switch (l.type) {
    case LightType::Spot:
      if (!(l.innerAngle >= 0.0f && l.innerAngle <= l.outerAngle && l.outerAngle > 0.0f &&
            l.outerAngle <= 0.5f * kPi + 1e-6f))
        fail(l.name, "spot angles must satisfy 0 <= inner <= outer <= 90 degrees, outer > 0");
      break;
    case LightType::Sun:
      if (!(l.angularDiameter > 0.0f && l.angularDiameter <= glm::radians(30.0f)))
        fail(l.name, "the sun's angular diameter must be in (0, 30] degrees");
      break;
    case LightType::Sphere:
    case LightType::Disk:
      positive(l.radius, "radius");
      break;
    case LightType::Tube:
      positive(l.radius, "radius");
      if (!(l.length >= 0.0f) || !std::isfinite(l.length)) fail(l.name, "length must be >= 0");
      break;
    case LightType::Rect:
      positive(l.width, "width");
      positive(l.height, "height");
      if (std::abs(glm::dot(l.up, l.direction)) > 1e-3f)
        fail(l.name, "up must be orthogonal to direction");
      break;
    case LightType::Point:
      break;
  }
}

shared::ShadingLight shadingLightOf(const Light& l) {
  shared::ShadingLight s{};
  s.type = static_cast<int>(l.type);
  s.position = l.position;
  s.direction = l.direction;
  s.up = l.up;
  s.color = l.color * (l.ies ? 1.0f : l.intensity);
  s.radius = l.type == LightType::Sun ? 0.5f * l.angularDiameter : l.radius;
  s.width = l.type == LightType::Tube ? l.length : l.width;
  s.height = l.height;
  s.cosInner = std::cos(l.innerAngle);
  s.cosOuter = std::cos(l.outerAngle);
  s.invSquaredRange = l.range > 0.0f ? 1.0f / (l.range * l.range) : 0.0f;
  return s;
}

std::vector<Light> parseLights(std::string_view text, const std::string& name,
                               const std::filesystem::path& baseDirectory, SpotLumens spotLumens) {
  const Json root = parseJsonText<Json>(text, name);
  if (!root.is_object() || !root.contains("lights") || !root["lights"].is_array())
    fail(name, "expected {\"lights\": [ ... ]}");
  for (const auto& [key, v] : root.items())
    if (key != "lights") fail(name, fmt::format("unknown field \"{}\"", key));
  if (root["lights"].size() > 4096) fail(name, "more than 4096 lights");
  std::vector<Light> lights;
  for (std::size_t i = 0; i < root["lights"].size(); ++i)
    lights.push_back(readLight(root["lights"][i], fmt::format("{}: light {}", name, i),
                               baseDirectory, spotLumens));
  return lights;
}

std::string lightJson(const Light& light) {
  const auto vec = [](glm::vec3 v) { return Json::array({v.x, v.y, v.z}); };
  // Angles to 1e-5 degree: a float's radians brought back to degrees may land a hair past a
  // bound the reader checks (30 degrees: 30.0000019).
  const auto degrees = [](float radians) {
    return std::round(static_cast<double>(glm::degrees(radians)) * 1e5) / 1e5;
  };
  Json j = {{"type", std::string(lightTypeName(light.type))}};
  const LightType t = light.type;
  if (t != LightType::Sun) j["position"] = vec(light.position);
  if (t == LightType::Tube)
    j["axis"] = vec(light.direction);
  else if (t != LightType::Point && t != LightType::Sphere)
    j["direction"] = vec(light.direction);
  if (t == LightType::Spot) {
    j["inner_angle"] = degrees(light.innerAngle);
    j["outer_angle"] = degrees(light.outerAngle);
  }
  if (t == LightType::Sun) j["angular_diameter"] = degrees(light.angularDiameter);
  if (t == LightType::Sphere || t == LightType::Disk || t == LightType::Tube)
    j["radius"] = light.radius;
  if (t == LightType::Tube) j["length"] = light.length;
  if (t == LightType::Rect) {
    j["up"] = vec(light.up);
    j["width"] = light.width;
    j["height"] = light.height;
  }
  if (light.ies) {
    if (light.iesFile.empty())
      fail(light.name.empty() ? "light" : light.name,
           "its IES profile was not read from a file and cannot be written");
    j["ies"] = {{"file", light.iesFile.string()}, {"multiplier", light.iesScale}};
  } else {
    j["intensity"] = light.intensity;
    j["unit"] = t == LightType::Sun                             ? "lux"
                : t == LightType::Point || t == LightType::Spot ? "cd"
                                                                : "nit";
  }
  j["color"] = vec(light.color);
  if (light.range > 0.0f) j["range"] = light.range;
  return j.dump();
}

std::string lightsFileText(const std::vector<Light>& lights) {
  std::string text = "{\"lights\": [";
  for (std::size_t i = 0; i < lights.size(); ++i)
    text += (i ? ",\n  " : "\n  ") + lightJson(lights[i]);
  return text + "\n]}\n";
}

std::vector<Light> readLightsFile(const std::filesystem::path& path, SpotLumens spotLumens) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  return parseLights(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                     path.string(), path.parent_path(), spotLumens);
}

}  // namespace ibl
