// Linearly transformed cosines (ibl/shared/ltc.h) against quadrature written here: the clipped
// polygon's form factor against the cosine integrated over the light.
#include <gtest/gtest.h>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "ibl/shared/ltc.h"
#include "support/numbers.hpp"
#include "support/quadrature.hpp"

namespace s = ibl::shared;
using ibl::test::direction;
using ibl::test::kCosine;
using ibl::test::kPi;
using ibl::test::Rect;
using ibl::test::rectToward;

// With the cosine itself (the identity entry) the clipped polygon's vector is the irradiance
// vector of Arvo 1995, (1 / pi) times the integral of w over the polygon's part above the
// horizon: its z is Lambert's form factor. Against quadrature over rects in front of, beside and
// straddling the horizon.
TEST(Ltc, PolygonFormFactorIsExact) {
  for (double theta : {0.0, 40.0, 75.0, 90.0, 105.0})
    for (double tilt : {0.0, 0.6}) {
      const Rect r = rectToward(direction(theta, 30.0), 1.5, tilt, 1.2, 0.7);
      const s::LtcFrame f = s::ltcFrame(glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), kCosine);
      const glm::vec3 got = s::ltcFrameToWorld(
          f, s::ltcQuadIntegral(f, r.corner(0), r.corner(1), r.corner(2), r.corner(3)));
      for (int k = 0; k < 3; ++k) {
        const double expected =
            r.integrate([&](glm::dvec3 w) { return w.z > 0.0 ? w[k] : 0.0; }) / kPi;
        EXPECT_NEAR(got[k], expected, 2e-5) << theta << " " << tilt << " " << k;
      }
    }
}
