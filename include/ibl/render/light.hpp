#pragma once
// API: stable
// Analytic lights in photometric units (Lagarde & de Rousiers 2014, "Moving Frostbite to
// Physically Based Rendering", section 4): what a scene holds, how a lights file describes them,
// and how the real-time shading (ibl/shared/lights.h) and the reference (light_sampling.hpp)
// read them.
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "ibl/io/ies.hpp"
#include "ibl/shared/light_record.h"

namespace ibl {

enum class LightType { Point, Spot, Sun, Sphere, Disk, Tube, Rect };

// "point", "spot", ... as the lights file spells them.
std::string_view lightTypeName(LightType type);

// Positions and sizes in scene units (meters for glTF: nits and lumens assume meters).
struct Light {
  LightType type = LightType::Point;
  std::string name;                        // for messages: "lights.json: light 2 (spot)"
  glm::vec3 position{0.0f};                // all but the sun; tube and rect: the center
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // unit. Spot: where it shines; sun: toward the sun;
                                           // disk, rect: the emitting side; tube: the axis
  glm::vec3 up{0.0f, 1.0f, 0.0f};          // rect: along its height, orthogonal to direction
  glm::vec3 color{1.0f};                   // linear Rec.709, multiplies the intensity
  // cd (point, spot), lx on a surface facing the sun (sun), nit (area lights).
  float intensity = 0.0f;
  float radius = 0.0f;                // sphere, disk, tube; scene units
  float length = 0.0f;                // tube: of the segment between the caps' centers
  float width = 0.0f, height = 0.0f;  // rect; scene units
  float innerAngle = 0.0f, outerAngle = 0.785398163f;  // spot: half-angles, radians
  float angularDiameter = 0.00925024504f;              // sun: radians (0.53 degrees)
  float range = 0.0f;  // influence radius with the smooth window, scene units; 0: none

  // Point and spot: a photometric profile, its candela x iesScale replacing `intensity` (the
  // web's nadir along `direction`, or down (-Y) for a point light; its 0-degree plane toward
  // iesHorizontalAxis()).
  std::shared_ptr<const IesProfile> ies;
  float iesScale = 1.0f;          // multiplier of the profile's candela
  std::filesystem::path iesFile;  // the profile's file, as read (lightJson writes it back)

  bool isPunctual() const { return type == LightType::Point || type == LightType::Spot; }
  // Punctual lights: the luminous intensity (cd, before color) toward unit direction w from
  // the light (the profile's value, or `intensity`).
  float intensityToward(glm::vec3 w) const;
  // The axis of the profile's nadir and the direction of its 0-degree plane.
  glm::vec3 iesNadir() const;
  glm::vec3 iesHorizontalAxis() const;
  // The luminous power in lumens, times the color's luminance (the sun: none, 0).
  double power() const;
};

// The light as the shading reads it (ibl/shared/light_record.h; an IES profile's value is applied
// by the caller through intensityToward: the shading light's color then carries color alone).
shared::ShadingLight shadingLightOf(const Light& light);

// How `"unit": "lm"` becomes a spot's intensity: spread over its cone (I = phi / (2 pi (1 -
// cos outer)), the physical rule, default) or Frostbite's I = phi / pi.
enum class SpotLumens { Physical, Frostbite };

// Parses a lights file's JSON text (format in the README: {"lights": [ {...}, ... ]}); IES files
// are found relative to `baseDirectory`. Throws Error("<name>: light <i> (<type>): <problem>")
// for unknown or missing fields, types or units, and values out of range.
std::vector<Light> parseLights(std::string_view text, const std::string& name,
                               const std::filesystem::path& baseDirectory,
                               SpotLumens spotLumens = SpotLumens::Physical);
// The same for a file (IES files relative to its directory); errors name it.
std::vector<Light> readLightsFile(const std::filesystem::path& path,
                                  SpotLumens spotLumens = SpotLumens::Physical);

// A light as one entry of a lights file (JSON text of the object): its type, its placement and
// size as the type takes them (angles in degrees), its intensity in cd, lux or nit (an IES light:
// {"file": the profile's path, "multiplier": iesScale} instead), its color and range; what
// `ibl sky --sun-json`, the manifests of bakes with a sun and the viewer's saved lights hold,
// and parseLights reads back. Throws Error for a light with a profile but no iesFile.
std::string lightJson(const Light& light);
// A lights file of `lights`: {"lights": [...]}, one light per line.
std::string lightsFileText(const std::vector<Light>& lights);

// Throws Error(light.name: ...) unless the light's fields are finite and in range (sizes > 0,
// 0 <= inner <= outer <= 90 degrees, unit directions, ...). Every reader calls it.
void checkLight(const Light& light);

}  // namespace ibl
