// The photometric units of ibl/shared/light_units.h against integrals written here: the power of
// a spot's cone integrated over the sphere, luminance conversions against the far-field
// intensity of the same light, and the punctual attenuation's window and falloff.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/vec3.hpp>

#include "ibl/shared/light_units.h"
#include "ibl/shared/lights_frostbite.h"
#include "support/numbers.hpp"

namespace s = ibl::shared;

namespace {

using ibl::test::kPi;

}  // namespace

// A spot converted from power puts exactly that power into its cone (inner = outer: the
// falloff's ramp is 0.001 wide in cos), integrated over the sphere.
TEST(Lights, SpotPowerFillsItsCone) {
  const double phi = 800.0;
  for (double outerDegrees : {10.0, 45.0, 90.0}) {
    const float cosOuter = static_cast<float>(std::cos(outerDegrees * kPi / 180.0));
    const float intensity = s::spotIntensityFromPower(static_cast<float>(phi), cosOuter, true);
    constexpr int kSteps = 200000;
    double power = 0.0;
    for (int i = 0; i < kSteps; ++i) {  // over cos(angle) in [-1, 1]: d(omega) = 2 pi d(cos)
      const double c = -1.0 + (i + 0.5) * 2.0 / kSteps;
      power += intensity *
               s::spotAngleAttenuation(static_cast<float>(c), cosOuter + 0.001f, cosOuter) * 2.0 *
               kPi * 2.0 / kSteps;
    }
    // The ramp's 0.001 in cos holds about a third of 0.001 / (1 - cos outer) of the power less.
    EXPECT_NEAR(power / phi, 1.0, 0.001 / (1.0 - cosOuter)) << outerDegrees;
  }
  EXPECT_FLOAT_EQ(s::spotIntensityFromPower(100.0f, 0.5f, false), 100.0f / s::kPi);
}

// Luminance from power, checked against the light seen from far away: a sphere of power phi is
// a point of intensity phi / 4 pi; a one-sided disk or rectangle of power phi has intensity
// phi / pi along its normal (a Lambertian emitter's peak, L times its area).
TEST(Lights, LuminanceFromPowerMatchesTheFarField) {
  const float phi = 1000.0f, d = 200.0f;
  const glm::vec3 n(0, 0, 1), toLight(0, 0, d);
  const float farE = s::pointIntensityFromPower(phi) / (d * d);
  EXPECT_NEAR(s::sphereIlluminanceFactor(n, toLight, 0.5f) * s::sphereLuminanceFromPower(phi, 0.5f),
              farE, 1e-4f * farE);
  EXPECT_NEAR(s::diskIlluminanceFactor(n, toLight, 0.5f, -n) * s::diskLuminanceFromPower(phi, 0.5f),
              phi / s::kPi / (d * d), 1e-4f * farE);
  EXPECT_NEAR(s::rectLuminanceFromPower(phi, 2.0f, 0.5f) * 2.0f * 0.5f, phi / s::kPi, 1e-3f);
  // A tube of length 0 is a sphere.
  EXPECT_NEAR(s::tubeLuminanceFromPower(phi, 0.3f, 0.0f), s::sphereLuminanceFromPower(phi, 0.3f),
              1e-6f);
}

TEST(Lights, DistanceWindowAndSpotFalloff) {
  const float invR2 = 1.0f / (4.0f * 4.0f);
  EXPECT_FLOAT_EQ(s::smoothDistanceWindow(0.0f, invR2), 1.0f);
  EXPECT_FLOAT_EQ(s::smoothDistanceWindow(2.0f * 2.0f, invR2),
                  (1.0f - 1.0f / 16.0f) * (1.0f - 1.0f / 16.0f));
  EXPECT_FLOAT_EQ(s::smoothDistanceWindow(4.0f * 4.0f, invR2), 0.0f);
  EXPECT_FLOAT_EQ(s::smoothDistanceWindow(9.0f, 0.0f), 1.0f);  // no radius: no window
  EXPECT_FLOAT_EQ(s::distanceAttenuation(9.0f, 0.0f), 1.0f / 9.0f);
  EXPECT_FLOAT_EQ(s::distanceAttenuation(0.0f, 0.0f), 1e4f);  // 1 cm at the least
  const float cosInner = std::cos(0.2f), cosOuter = std::cos(0.4f);
  EXPECT_FLOAT_EQ(s::spotAngleAttenuation(1.0f, cosInner, cosOuter), 1.0f);
  EXPECT_FLOAT_EQ(s::spotAngleAttenuation(std::cos(0.5f), cosInner, cosOuter), 0.0f);
  const float mid = 0.5f * (cosInner + cosOuter);
  EXPECT_NEAR(s::spotAngleAttenuation(mid, cosInner, cosOuter), 0.25f, 1e-5f);
}
