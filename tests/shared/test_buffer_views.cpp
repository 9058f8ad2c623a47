// The buffer views' colors and the validation view's verdicts (ibl/shared/buffer_views.h): gray
// values that a display's sRGB encoding turns back into the value, the heat map's knots, and
// the verdicts on materials whose base colors were measured (Filament's "Material properties"
// chart, sRGB), at and beside the thresholds taken from "The PBR Guide".
#include <gtest/gtest.h>

#include "ibl/shared/buffer_views.h"

namespace ibl {
namespace {

using shared::materialValidation;

// A chart's sRGB code triple as linear color.
glm::vec3 linearOf(float r, float g, float b) {
  return shared::srgbToLinear(glm::vec3(r, g, b) / 255.0f);
}

glm::vec3 encoded(glm::vec3 linear) {
  return {shared::linearToSrgb(linear.x), shared::linearToSrgb(linear.y),
          shared::linearToSrgb(linear.z)};
}

TEST(BufferViews, GrayValuesEncodeToThemselves) {
  for (float v : {0.0f, 0.1f, 0.3f, 0.5f, 0.8f, 1.0f}) {
    const glm::vec3 e = encoded(shared::grayOfValue(v));
    EXPECT_NEAR(e.x, v, 1e-5f);
    EXPECT_EQ(e.x, e.y);
    EXPECT_EQ(e.y, e.z);
  }
  EXPECT_NEAR(encoded(shared::grayOfValue(1.7f)).x, 1.0f, 1e-6f);  // clamped
}

TEST(BufferViews, HeatMapPassesItsKnots) {
  const glm::vec3 knots[6] = {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  for (int k = 0; k < 6; ++k) {
    const glm::vec3 e = encoded(shared::heatMapColor(0.2f * static_cast<float>(k)));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c], knots[k][c], 1e-5f) << k << " " << c;
  }
  // Halfway between cyan and green; beyond the ends, the ends.
  EXPECT_NEAR(encoded(shared::heatMapColor(0.5f)).z, 0.5f, 1e-5f);
  EXPECT_NEAR(encoded(shared::heatMapColor(3.0f)).x, 1.0f, 1e-6f);
  EXPECT_NEAR(encoded(shared::heatMapColor(-1.0f)).z, 0.0f, 1e-6f);
}

TEST(BufferViews, MeasuredMaterialsArePlausible) {
  const glm::vec3 none(0.0f);
  // Dielectrics: coal, rubber, mud, wood, vegetation, brick, sand, concrete.
  const glm::vec3 dielectrics[] = {{50, 50, 50},    {53, 53, 53},   {85, 61, 49},
                                   {135, 92, 60},   {123, 130, 78}, {148, 125, 117},
                                   {177, 168, 132}, {192, 191, 187}};
  for (glm::vec3 c : dielectrics)
    EXPECT_EQ(materialValidation(linearOf(c.x, c.y, c.z), 0.0f, 0.0f, none),
              shared::kValidationPlausible)
        << c.x;
  // Metals: silver, aluminum, platinum, iron, titanium, copper, gold, brass.
  const glm::vec3 metals[] = {{250, 249, 245}, {244, 245, 245}, {214, 209, 200}, {192, 189, 186},
                              {206, 200, 194}, {251, 216, 184}, {255, 220, 157}, {244, 228, 173}};
  for (glm::vec3 c : metals)
    EXPECT_EQ(materialValidation(linearOf(c.x, c.y, c.z), 1.0f, 0.0f, none),
              shared::kValidationPlausible)
        << c.x;
}

TEST(BufferViews, ValidationThresholdsAreTheGuides) {
  const glm::vec3 none(0.0f);
  const auto gray = [](float code) { return linearOf(code, code, code); };
  // Dielectrics from 30 to 240 of 255.
  EXPECT_EQ(materialValidation(gray(29), 0.0f, 0.0f, none), shared::kValidationTooDark);
  EXPECT_EQ(materialValidation(gray(31), 0.0f, 0.0f, none), shared::kValidationPlausible);
  EXPECT_EQ(materialValidation(gray(239), 0.0f, 0.0f, none), shared::kValidationPlausible);
  EXPECT_EQ(materialValidation(gray(241), 0.0f, 0.0f, none), shared::kValidationTooBright);
  // Metals from 180 of 255 (no upper bound: a perfect mirror is a metal's limit).
  EXPECT_EQ(materialValidation(gray(179), 1.0f, 0.0f, none), shared::kValidationTooDark);
  EXPECT_EQ(materialValidation(gray(181), 1.0f, 0.0f, none), shared::kValidationPlausible);
  EXPECT_EQ(materialValidation(gray(255), 1.0f, 0.0f, none), shared::kValidationPlausible);
  // Metallic within 0.1 of 0 or 1 counts as either; between, only where it changes.
  EXPECT_EQ(materialValidation(gray(120), 0.09f, 0.0f, none), shared::kValidationPlausible);
  EXPECT_EQ(materialValidation(gray(200), 0.91f, 0.0f, none), shared::kValidationPlausible);
  EXPECT_EQ(materialValidation(gray(200), 0.5f, 0.0f, none), shared::kValidationPartlyMetallic);
  EXPECT_EQ(materialValidation(gray(200), 0.5f, 0.019f, none), shared::kValidationPartlyMetallic);
  EXPECT_EQ(materialValidation(gray(200), 0.5f, 0.05f, none), shared::kValidationPlausible);
  // Emission of at most 1 (glTF's factor without KHR_materials_emissive_strength) before all.
  EXPECT_EQ(materialValidation(gray(120), 0.0f, 0.0f, glm::vec3(0.5f, 1.0f, 0.2f)),
            shared::kValidationEmissiveWithoutUnits);
  EXPECT_EQ(materialValidation(gray(10), 0.5f, 0.0f, glm::vec3(0.0f, 0.0f, 0.01f)),
            shared::kValidationEmissiveWithoutUnits);
  EXPECT_EQ(materialValidation(gray(120), 0.0f, 0.0f, glm::vec3(400.0f)),
            shared::kValidationPlausible);
}

TEST(BufferViews, VerdictsHaveTheirOwnColors) {
  const glm::vec3 base(0.3f);
  const glm::vec3 plausible = shared::validationColor(shared::kValidationPlausible, base);
  EXPECT_EQ(plausible.x, plausible.y);  // gray
  EXPECT_EQ(plausible.y, plausible.z);
  const int verdicts[] = {shared::kValidationEmissiveWithoutUnits,
                          shared::kValidationPartlyMetallic, shared::kValidationTooDark,
                          shared::kValidationTooBright};
  for (int a : verdicts) {
    const glm::vec3 ca = shared::validationColor(a, base);
    EXPECT_FALSE(ca.x == ca.y && ca.y == ca.z) << a << " is not gray";
    for (int b : verdicts) {
      if (a != b) {
        EXPECT_NE(ca, shared::validationColor(b, base)) << a << " " << b;
      }
    }
  }
}

}  // namespace
}  // namespace ibl
