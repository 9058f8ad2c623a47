// The light colors of ibl/math/color.hpp against the Planckian locus as a published fit gives it.
#include <gtest/gtest.h>
#include <glm/vec3.hpp>

#include "ibl/math/color.hpp"

// Light colors from a temperature: the chromaticity of blackbodyColor (converted back to XYZ
// with the inverse of the Rec.709 matrix, the sRGB standard's) against the cubic-spline fit of
// the Planckian locus by Kang et al. 2002 (J. Korean Phys. Soc. 41(6)), from 2000 to 20000 K;
// unit luminance.
TEST(Lights, KelvinColorsFollowThePlanckianLocus) {
  for (double t : {2000.0, 2700.0, 3500.0, 4500.0, 5500.0, 6500.0, 8000.0, 12000.0, 20000.0}) {
    const glm::vec3 rgb = ibl::blackbodyColor(static_cast<float>(t));
    EXPECT_NEAR(0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z, 1.0, 1e-5) << t;
    // Linear Rec.709 to XYZ (IEC 61966-2-1).
    const double X = 0.4124564 * rgb.x + 0.3575761 * rgb.y + 0.1804375 * rgb.z;
    const double Y = 0.2126729 * rgb.x + 0.7151522 * rgb.y + 0.0721750 * rgb.z;
    const double Z = 0.0193339 * rgb.x + 0.1191920 * rgb.y + 0.9503041 * rgb.z;
    const double x = X / (X + Y + Z), y = Y / (X + Y + Z);
    const double u = 1e3 / t;  // the fit's variable, 10^3 / T
    const double xc = t <= 4000.0
                          ? -0.2661239 * u * u * u - 0.2343589 * u * u + 0.8776956 * u + 0.179910
                          : -3.0258469 * u * u * u + 2.1070379 * u * u + 0.2226347 * u + 0.240390;
    const double yc =
        t <= 2222.0
            ? -1.1063814 * xc * xc * xc - 1.34811020 * xc * xc + 2.18555832 * xc - 0.20219683
        : t <= 4000.0
            ? -0.9549476 * xc * xc * xc - 1.37418593 * xc * xc + 2.09137015 * xc - 0.16748867
            : 3.0817580 * xc * xc * xc - 5.87338670 * xc * xc + 3.75112997 * xc - 0.37001483;
    // The two fits differ by 0.0027 at 2000 K (the matching-function fit's red end), less than
    // 0.002 above; 100 K moves the locus by 0.01 or more there.
    const double tolerance = t < 2500.0 ? 3e-3 : 2e-3;
    EXPECT_NEAR(x, xc, tolerance) << t;
    EXPECT_NEAR(y, yc, tolerance) << t;
  }
  // Warm light is red-heavy, cold light blue-heavy.
  EXPECT_GT(ibl::blackbodyColor(2700.0f).x, ibl::blackbodyColor(2700.0f).z);
  EXPECT_LT(ibl::blackbodyColor(12000.0f).x, ibl::blackbodyColor(12000.0f).z);
}
