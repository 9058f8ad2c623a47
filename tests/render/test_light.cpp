// The lights file (--lights): every type and unit as the README documents it, checked by the
// light the shading then sees against the units' definitions (lumens over the sphere of
// directions by quadrature here), and each kind of mistake reported as one line naming the light.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/light.hpp"
#include "ibl/shared/lights.h"
#include "support/numbers.hpp"

using namespace ibl;

namespace {

using ibl::test::kPiF;

std::vector<Light> parse(const std::string& lights) {
  return parseLights(R"({"lights": [)" + lights + "]}", "lights.json", ".");
}

// The message of the error parsing `lights` throws ("" if none).
std::string errorOf(const std::string& lights) {
  try {
    parse(lights);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// The illuminance (lx) the shading (ibl/shared/lights.h, as the split sum and the viewer compute
// it by default: area lights through LTCs, whose diffuse form factors are exact) gets from
// `light` on a surface at p facing along n.
double illuminance(const Light& light, glm::vec3 p, glm::vec3 n) {
  const shared::ShadingLight s = shadingLightOf(light);
  shared::SplitSumSwitches ltc{};
  ltc.ltcAreaLights = true;
  return shared::lightIncidence(s, p, n, n, 0.5f, ltc, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f))
             .diffuseIlluminance *
         luminance(s.color);
}

// The light's intensity toward unit w (cd), as seen from far: the illuminance on a surface
// facing the light kDistance away, times the distance squared.
constexpr float kDistance = 200.0f;
double farIntensity(const Light& light, glm::vec3 w) {
  return illuminance(light, light.position + kDistance * w, -w) * kDistance * kDistance;
}

// The light's power (lm): its far-field intensity integrated over the sphere of directions, by
// the midpoint rule in (cos theta, phi) about the light's axis, 200 x 200 points.
double powerFromFarField(const Light& light) {
  constexpr int n = 200;
  const bool axial = light.type == LightType::Tube || light.type == LightType::Rect ||
                     light.type == LightType::Disk || light.type == LightType::Spot;
  const glm::vec3 z = axial ? light.direction : glm::vec3(0, 1, 0);
  const glm::vec3 x =
      glm::normalize(glm::cross(std::abs(z.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0), z));
  const glm::vec3 y = glm::cross(z, x);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double c = -1.0 + 2.0 * (i + 0.5) / n, sn = std::sqrt(1.0 - c * c);
    for (int j = 0; j < n; ++j) {
      const double phi = 2.0 * kPiF * (j + 0.5) / n;
      const glm::vec3 w =
          glm::normalize(static_cast<float>(sn * std::cos(phi)) * x +
                         static_cast<float>(sn * std::sin(phi)) * y + static_cast<float>(c) * z);
      sum += farIntensity(light, w);
    }
  }
  return sum * (2.0 / n) * (2.0 * kPiF / n);
}

}  // namespace

// Every type and unit of the file, checked by what the light then delivers (the shading's
// illuminance, lights.h) against the units' definitions, not the conversions' formulas: lumens
// are the light's far-field intensity integrated over the sphere of directions (`color`
// multiplies the intensity, so a colored light emits lumens times the color's luminance); a
// Lambertian emitter of luminance L and area A emits L A pi and has intensity L times its
// projected area; candela is the illuminance times d^2 on the axis; lux the illuminance on a
// surface facing the sun.
TEST(LightsFile, EveryTypeAndUnit) {
  const std::vector<Light> l = parse(R"(
    {"type": "point", "position": [1, 2, 3], "intensity": 1000, "unit": "lm"},
    {"type": "point", "position": [0, 1, 0], "radius": 0.1, "intensity": 500, "unit": "lm"},
    {"type": "spot", "position": [0, 3, 0], "direction": [0, -2, 0], "inner_angle": 20,
     "outer_angle": 40, "intensity": 100, "unit": "cd", "range": 8},
    {"type": "sun", "direction": [0, 1, 1], "intensity": 100000, "unit": "lux", "kelvin": 5800},
    {"type": "sphere", "position": [0, 1, 0], "radius": 0.5, "intensity": 200, "unit": "nit"},
    {"type": "disk", "position": [0, 1, 0], "direction": [0, -1, 0], "radius": 0.5,
     "intensity": 1000, "unit": "lm"},
    {"type": "tube", "position": [0, 1, 0], "axis": [1, 0, 0], "length": 1.2, "radius": 0.05,
     "intensity": 2000, "unit": "lm"},
    {"type": "rect", "position": [0, 2, 0], "direction": [0, -1, 0], "up": [0, 0.5, 1],
     "width": 2, "height": 0.5, "intensity": 3000, "unit": "lm", "color": [1, 0.5, 0.25]},
    {"type": "spot", "position": [0, 0, 0], "direction": [1, 0, 0], "inner_angle": 60,
     "outer_angle": 60, "intensity": 800, "unit": "lm"})");
  ASSERT_EQ(l.size(), 9u);
  const LightType types[] = {LightType::Point, LightType::Sphere, LightType::Spot,
                             LightType::Sun,   LightType::Sphere, LightType::Disk,
                             LightType::Tube,  LightType::Rect,   LightType::Spot};
  for (std::size_t i = 0; i < l.size(); ++i) EXPECT_EQ(l[i].type, types[i]) << i;
  const double pi = kPiF, rectColor = luminance(glm::vec3(1, 0.5f, 0.25f));
  // Lumens: the far field over the sphere gives them back (within 1e-3: the quadrature, and the
  // far field at 200 m of lights up to 2 m wide).
  std::vector<double> power(l.size(), 0.0);
  for (std::size_t i : {0u, 1u, 4u, 5u, 6u, 7u, 8u}) power[i] = powerFromFarField(l[i]);
  EXPECT_NEAR(power[0], 1000.0, 1.0);
  EXPECT_NEAR(power[1], 500.0, 0.5);  // a point with a radius: a sphere
  EXPECT_NEAR(power[5], 1000.0, 1.0);
  EXPECT_NEAR(power[6], 2000.0, 2.0);
  EXPECT_NEAR(power[7], 3000.0 * rectColor, 2.0);
  // A spot's lumens fill its cone (inner = outer: the falloff's ramp is 0.001 wide in cos, where
  // it holds 2/3 x 0.001 / (1 - cos 60) = 0.13 % less); nothing outside it.
  EXPECT_NEAR(power[8], 800.0, 1.6);
  EXPECT_EQ(farIntensity(l[8], glm::normalize(glm::vec3(1.0f, 2.0f, 0.0f))), 0.0);
  // Nits: the sphere's intensity is L times its projected disk, its power L pi times its area.
  EXPECT_NEAR(farIntensity(l[4], glm::vec3(0, 0, 1)), 200.0 * pi * 0.25, 0.05);
  EXPECT_NEAR(power[4], 200.0 * pi * (4.0 * pi * 0.25), 0.5);
  // One-sided Lambertian emitters of power phi: intensity phi / pi along the normal (L A), none
  // behind.
  EXPECT_NEAR(farIntensity(l[5], glm::vec3(0, -1, 0)), 1000.0 / pi, 0.1);
  EXPECT_EQ(farIntensity(l[5], glm::vec3(0, 1, 0)), 0.0);
  EXPECT_NEAR(farIntensity(l[7], glm::vec3(0, -1, 0)), 3000.0 / pi * rectColor, 0.2);
  // Candela: E d^2 on the axis and inside the inner cone, 0.5 m away (the range's window is
  // 1 - 3e-5 there); nothing beyond the outer cone or the range.
  const glm::vec3 spot(0, 3, 0);
  EXPECT_NEAR(illuminance(l[2], spot - glm::vec3(0, 0.5f, 0), glm::vec3(0, 1, 0)) * 0.25, 100.0,
              0.01);
  const glm::vec3 w15 = glm::normalize(glm::vec3(std::sin(0.26f), -std::cos(0.26f), 0.0f));
  EXPECT_NEAR(illuminance(l[2], spot + 0.5f * w15, -w15) * 0.25, 100.0, 0.01);
  const glm::vec3 w45 = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
  EXPECT_EQ(illuminance(l[2], spot + 0.5f * w45, -w45), 0.0);
  EXPECT_EQ(illuminance(l[2], spot - glm::vec3(0, 8.5f, 0), glm::vec3(0, 1, 0)), 0.0);
  // Lux: the illuminance on a surface facing the sun, and Lambert's cosine at 60 degrees.
  const glm::vec3 toSun = glm::normalize(glm::vec3(0, 1, 1));
  EXPECT_NEAR(illuminance(l[3], glm::vec3(0.0f), toSun), 100000.0, 10.0);
  const glm::vec3 at60 = glm::normalize(toSun + std::tan(glm::radians(60.0f)) * glm::vec3(1, 0, 0));
  EXPECT_NEAR(illuminance(l[3], glm::vec3(0.0f), at60), 50000.0, 10.0);
  EXPECT_NEAR(glm::degrees(l[3].angularDiameter), 0.53, 1e-5);  // the README's default
  EXPECT_GT(l[3].color.z, 0.75f * l[3].color.x);                // 5800 K: near white, a little warm
  // The fields as given: directions made unit, up made orthogonal, the spot's angles in radians.
  EXPECT_EQ(l[0].position, glm::vec3(1, 2, 3));
  EXPECT_EQ(l[2].direction, glm::vec3(0, -1, 0));
  EXPECT_NEAR(l[2].outerAngle, 40.0 * pi / 180.0, 1e-6);
  EXPECT_EQ(l[2].range, 8.0f);
  EXPECT_NEAR(glm::dot(l[7].up, l[7].direction), 0.0f, 1e-6f);
  EXPECT_NEAR(l[7].up.z, 1.0f, 1e-6f);
  EXPECT_EQ(l[7].color, glm::vec3(1, 0.5f, 0.25f));
  // Light::power (what the reference renderer weighs lights by) agrees with the far field.
  for (std::size_t i : {0u, 1u, 4u, 5u, 6u, 7u, 8u})
    EXPECT_NEAR(l[i].power(), power[i], 2e-3 * l[i].power()) << i;
}

TEST(LightsFile, MistakesNameTheLight) {
  const struct {
    std::string lights, message;
  } cases[] = {
      {R"({"type": "laser", "intensity": 1, "unit": "cd"})",
       "lights.json: light 0: unknown type \"laser\""},
      {R"({"type": "point", "position": [0, 0, 0], "intensity": 1, "unit": "cd", "size": 2})",
       "lights.json: light 0 (point): unknown field \"size\""},
      {R"({"type": "point", "position": [0, 0, 0], "intensity": 1, "unit": "cd"},
          {"type": "spot", "position": [0, 0, 0], "intensity": 1, "unit": "cd"})",
       "lights.json: light 1 (spot): missing \"direction\""},
      {R"({"type": "sun", "direction": [0, 1, 0], "intensity": 1, "unit": "nit"})",
       "lights.json: light 0 (sun): unit \"nit\" is not one of \"lux\""},
      {R"({"type": "rect", "position": [0, 0, 0], "direction": [0, 1, 0], "up": [0, 2, 0],
          "width": 1, "height": 1, "intensity": 1, "unit": "nit"})",
       "lights.json: light 0 (rect): \"up\" is parallel to \"direction\""},
      {R"({"type": "spot", "position": [0, 0, 0], "direction": [0, -1, 0], "inner_angle": 50,
          "outer_angle": 40, "intensity": 1, "unit": "cd"})",
       "lights.json: light 0 (spot): angles must satisfy"},
      {R"({"type": "disk", "position": [0, 0, 0], "direction": [0, -1, 0], "radius": -1,
          "intensity": 1, "unit": "nit"})",
       "lights.json: light 0 (disk): \"radius\" must be positive"},
      {R"({"type": "sphere", "position": [0, 0, 0], "radius": 1, "intensity": 1, "unit": "nit",
          "color": [1, 1, 1], "kelvin": 3000})",
       "lights.json: light 0 (sphere): give \"color\" or \"kelvin\", not both"},
      {R"({"type": "point", "position": [0, 0, 0], "intensity": -5, "unit": "cd"})",
       "lights.json: light 0 (point): \"intensity\" must not be negative"},
      {R"({"type": "point", "position": [0, "a", 0], "intensity": 5, "unit": "cd"})",
       "lights.json: light 0 (point): \"position\" must be an array of three numbers"},
      {R"({"type": "point", "position": [0, 0, 0], "intensity": 5, "unit": "cd",
          "ies": "missing.ies"})",
       "missing.ies"},
  };
  for (const auto& c : cases) {
    const std::string message = errorOf(c.lights);
    EXPECT_NE(message.find(c.message), std::string::npos) << message << "\nexpected: " << c.message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_THROW(parseLights("{\"lights\": [", "bad.json", "."), Error);
  EXPECT_THROW(parseLights("{\"light\": []}", "bad.json", "."), Error);
}

// A file that is not JSON is named with the line and column of the first mistake (counted here
// by hand: lines from 1, columns in bytes from 1) and the problem in words; a number beyond a
// double's range says so where it starts; bytes of a binary file are escaped, never printed.
TEST(LightsFile, JsonMistakesNameTheLineAndColumn) {
  const auto messageOf = [](const std::string& text) -> std::string {
    try {
      parseLights(text, "f.json", ".");
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  const std::pair<std::string, std::string> cases[] = {
      {"{\"lights\": [\n  {\"type\": \"point\",\n",
       "f.json: line 3, column 1: unexpected end of input; expected string literal"},
      {"{\"lights\": [}\n", "f.json: line 1, column 13: unexpected '}'"},
      {"{\"lights\": []}\r\n\n  x", "f.json: line 3, column 3: "},
      {"{\"lights\": [{\"type\": \"point\", \"intensity\": 1e999}]}",
       "f.json: line 1, column 44: the number 1e999 is out of range"},
      {"{\"lights\":\n [{\"intensity\": -2E+400}]}",
       "f.json: line 2, column 17: the number -2E+400 is out of range"},
      {"", "f.json: line 1, column 1: unexpected end of input"},
      {std::string("\x76\x2f\x31\x01\xff\x00\x1b", 7), "f.json: line 1, column 1: "},
  };
  for (const auto& [text, expected] : cases) {
    const std::string message = messageOf(text);
    EXPECT_EQ(message.rfind(expected, 0), 0u) << message << "\nexpected: " << expected;
    for (const char c : message)
      EXPECT_TRUE(c >= 0x20 && c < 0x7f)
          << "a byte " << int(static_cast<unsigned char>(c)) << " in: " << message;
  }
}

// lightsFileText written and parsed back: every type with every field it takes (odd values, a
// range, a color), and an IES light through its profile's file, come back as they were (the
// angles through degrees, to float rounding); the text names each light's units.
TEST(LightsFile, WrittenLightsReadBackTheSame) {
  const std::vector<Light> lights = parse(R"(
    {"type": "point", "position": [1, 2, 3], "intensity": 120, "unit": "cd", "range": 7},
    {"type": "spot", "position": [0, 3, 0], "direction": [0.6, -0.8, 0], "inner_angle": 12.5,
     "outer_angle": 31, "intensity": 900, "unit": "cd", "color": [1, 0.5, 0.25]},
    {"type": "sun", "direction": [0, 0.6, 0.8], "intensity": 90000, "unit": "lux",
     "angular_diameter": 0.7},
    {"type": "sphere", "position": [-1, 1, 0], "radius": 0.15, "intensity": 5000, "unit": "nit"},
    {"type": "disk", "position": [0, 2, -1], "direction": [0, 0, 1], "radius": 0.4,
     "intensity": 2000, "unit": "nit", "kelvin": 3200},
    {"type": "tube", "position": [0, 2.5, 0], "axis": [1, 0, 0], "length": 1.2, "radius": 0.05,
     "intensity": 3000, "unit": "nit"},
    {"type": "rect", "position": [0, 2.2, 1.2], "direction": [0, -0.8, -0.6], "up": [0, 0.6, -0.8],
     "width": 1.6, "height": 0.8, "intensity": 700, "unit": "nit"})");
  const std::string text = lightsFileText(lights);
  EXPECT_NE(text.find("\"unit\":\"lux\""), std::string::npos) << text;
  const std::vector<Light> back = parseLights(text, "saved.json", ".");
  ASSERT_EQ(back.size(), lights.size());
  const auto near = [](glm::vec3 a, glm::vec3 b) { return glm::length(a - b) < 1e-5f; };
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light &a = lights[i], &b = back[i];
    EXPECT_EQ(a.type, b.type) << i;
    EXPECT_TRUE(near(a.position, b.position)) << i;
    EXPECT_TRUE(near(a.direction, b.direction)) << i;
    EXPECT_TRUE(near(a.up, b.up)) << i;
    EXPECT_TRUE(near(a.color, b.color)) << i;
    EXPECT_FLOAT_EQ(a.intensity, b.intensity) << i;
    EXPECT_FLOAT_EQ(a.radius, b.radius) << i;
    EXPECT_FLOAT_EQ(a.length, b.length) << i;
    EXPECT_FLOAT_EQ(a.width, b.width) << i;
    EXPECT_FLOAT_EQ(a.height, b.height) << i;
    EXPECT_NEAR(a.innerAngle, b.innerAngle, 1e-6f) << i;
    EXPECT_NEAR(a.outerAngle, b.outerAngle, 1e-6f) << i;
    EXPECT_NEAR(a.angularDiameter, b.angularDiameter, 1e-7f) << i;
    EXPECT_FLOAT_EQ(a.range, b.range) << i;
  }
  // An IES light: the same candela in every direction, from the file it names.
  const std::vector<Light> ies = parseLights(
      R"({"lights": [{"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0],
          "inner_angle": 20, "outer_angle": 40, "ies": "downlight.ies", "intensity": 800,
          "unit": "lm"}]})",
      "ies.json", IBL_TEST_DATA "/lights");
  const std::vector<Light> iesBack = parseLights(lightsFileText(ies), "saved.json", "/");
  ASSERT_EQ(iesBack.size(), 1u);
  for (const glm::vec3 w : {glm::vec3(0, -1, 0), glm::normalize(glm::vec3(0.3f, -1, 0.2f)),
                            glm::normalize(glm::vec3(-0.5f, -1, 0.4f))})
    EXPECT_FLOAT_EQ(iesBack[0].intensityToward(w), ies[0].intensityToward(w));
  // A profile made in memory has no file to name.
  Light made = ies[0];
  made.iesFile.clear();
  EXPECT_THROW(lightJson(made), Error);
}
