// The lights file (--lights): every type and unit as the README documents it, the conversions
// from lumens done by hand here, and each kind of mistake reported as one line naming the light.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/light.hpp"

using namespace ibl;

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

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

}  // namespace

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
     "width": 2, "height": 0.5, "intensity": 3000, "unit": "lm", "color": [1, 0.5, 0.25]})");
  ASSERT_EQ(l.size(), 8u);
  EXPECT_EQ(l[0].type, LightType::Point);
  EXPECT_FLOAT_EQ(l[0].intensity, 1000.0f / (4.0f * kPi));
  EXPECT_EQ(l[0].position, glm::vec3(1, 2, 3));
  // A point light with a radius is a sphere: phi / (4 pi r^2 pi).
  EXPECT_EQ(l[1].type, LightType::Sphere);
  EXPECT_FLOAT_EQ(l[1].intensity, 500.0f / (4.0f * kPi * 0.01f * kPi));
  EXPECT_EQ(l[2].type, LightType::Spot);
  EXPECT_EQ(l[2].direction, glm::vec3(0, -1, 0));
  EXPECT_FLOAT_EQ(l[2].outerAngle, 40.0f * kPi / 180.0f);
  EXPECT_EQ(l[2].range, 8.0f);
  EXPECT_EQ(l[3].type, LightType::Sun);
  EXPECT_NEAR(l[3].angularDiameter, 0.53f * kPi / 180.0f, 1e-7f);
  EXPECT_NEAR(luminance(l[3].color), 1.0f, 1e-3f);
  EXPECT_GT(l[3].color.z, 0.75f * l[3].color.x);  // 5800 K: near white, a little warm
  EXPECT_FLOAT_EQ(l[4].intensity, 200.0f);
  EXPECT_FLOAT_EQ(l[5].intensity, 1000.0f / (kPi * 0.25f * kPi));
  EXPECT_FLOAT_EQ(l[6].intensity,
                  2000.0f / ((2.0f * kPi * 0.05f * 1.2f + 4.0f * kPi * 0.0025f) * kPi));
  EXPECT_FLOAT_EQ(l[7].intensity, 3000.0f / (2.0f * 0.5f * kPi));
  EXPECT_NEAR(glm::dot(l[7].up, l[7].direction), 0.0f, 1e-6f);  // made orthogonal
  EXPECT_NEAR(l[7].up.z, 1.0f, 1e-6f);
  EXPECT_EQ(l[7].color, glm::vec3(1, 0.5f, 0.25f));
  // Power back from the light: lumens in, lumens out.
  EXPECT_NEAR(l[0].power(), 1000.0, 0.1);
  EXPECT_NEAR(l[5].power(), 1000.0, 0.1);
  EXPECT_NEAR(l[6].power(), 2000.0, 0.2);
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
