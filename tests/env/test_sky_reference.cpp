// The physical sky's model against the path-traced reference written apart from it
// (pathTracedSkyRadiance, src/env/sky_reference.cpp).
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/env/sky.hpp"
#include "ibl/math/color.hpp"
#include "support/numbers.hpp"
#include "support/sky.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// The sky's horizontal illuminance (lux) by the model and by the path-traced reference over the
// same n x n directions, stratified and cosine-distributed (Malley: uniform points of the unit
// disk lifted to the hemisphere), E = pi times the mean radiance; the reference traces `paths`
// paths per band per direction.
struct HorizontalIlluminance {
  double model = 0.0, reference = 0.0;
};
HorizontalIlluminance horizontalIlluminanceBoth(const SkyParameters& p, int n, int paths) {
  const SkyModel sky(p);
  HorizontalIlluminance e;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = (i + 0.5) / n, phi = 2.0 * kPi * (j + 0.5) / n;
      const double rho = std::sqrt(u);
      const glm::vec3 d(static_cast<float>(rho * std::cos(phi)),
                        static_cast<float>(std::sqrt(1.0 - u)),
                        static_cast<float>(rho * std::sin(phi)));
      e.model += spectrumToXyz(sky.radiance(d)).y;
      e.reference +=
          spectrumToXyz(pathTracedSkyRadiance(p, d, paths, static_cast<unsigned>(1 + i * n + j))).y;
    }
  e.model *= kPi / (n * n);
  e.reference *= kPi / (n * n);
  return e;
}

}  // namespace

TEST(Sky, AgreesWithThePathTracedReference) {
  // The model against a volumetric path tracer written apart from it (pathTracedSkyRadiance:
  // delta tracking, every order of scattering, no tables), luminance per direction over a black
  // ground. Single scattering (the march, the optical-depth table, the phase functions) must
  // agree within the reference's noise; with every order, Hillaire's isotropic multiple
  // scattering must bring the model closer than single scattering alone, and stay within its
  // measured error (docs/sky.md: + at the zenith, - toward the horizon, the more so at low sun).
  // The reference's noise, measured over four seeds: 1 to 2 % (one standard deviation) with
  // 3000 paths per band, 0.5 to 1.4 % single scattering with 1500; each bound below is the
  // error measured here plus three of those and 1 %.
  struct Case {
    float sunElevation;
    glm::vec3 view;
    double bound;  // |model / reference - 1| with every order
  };
  const Case cases[] = {{30.0f, {0.0f, 1.0f, 0.0f}, 0.15},                             // +7.9 %
                        {30.0f, glm::normalize(glm::vec3(0.0f, 0.1f, -1.0f)), 0.17},   // -13.2 %
                        {30.0f, glm::normalize(glm::vec3(0.2f, 0.5f, 1.0f)), 0.11},    // -6.7 %
                        {6.0f, glm::normalize(glm::vec3(0.3f, 0.05f, -1.0f)), 0.31}};  // -26.0 %
  for (const Case& c : cases) {
    SkyParameters p = sunAt(c.sunElevation, 180.0f);
    p.groundAlbedo = 0.0f;
    const double full = spectrumToXyz(SkyModel(p).radiance(c.view)).y;
    const double referenceFull = spectrumToXyz(pathTracedSkyRadiance(p, c.view, 3000, 1)).y;
    const double referenceSingle = spectrumToXyz(pathTracedSkyRadiance(p, c.view, 1500, 2, 1)).y;
    p.multipleScattering = false;
    const double single = spectrumToXyz(SkyModel(p).radiance(c.view)).y;
    std::printf(
        "sun %4.1f, view (%5.2f %5.2f %5.2f): single %8.1f vs %8.1f (%+5.1f %%), all "
        "orders %8.1f vs %8.1f (%+5.1f %%) cd/m2\n",
        c.sunElevation, c.view.x, c.view.y, c.view.z, single, referenceSingle,
        100.0 * (single / referenceSingle - 1.0), full, referenceFull,
        100.0 * (full / referenceFull - 1.0));
    EXPECT_NEAR(single / referenceSingle, 1.0, 0.05);  // measured within 1.2 %
    EXPECT_LT(std::abs(full - referenceFull), std::abs(single - referenceFull));
    EXPECT_NEAR(full / referenceFull, 1.0, c.bound);
  }
  // The sky's horizontal illuminance, sun at 60 degrees over the default ground (albedo 0.3),
  // against the reference over the same 64 x 64 cosine-distributed directions, one path per band
  // each: measured +0.5 % here, +1.8 % and +5.2 % with other seeds (the reference's noise, 2.4 %,
  // the sun's aureole dominating it; the model's own error about +2.5 %, the zenith's excess and
  // the horizon's deficit partly cancelling): the bound is that mean plus three deviations. Single
  // scattering alone is checked against a deterministic integration within 0.8 %
  // (SingleScatteringIlluminanceMatchesAnIntegrationWrittenHere).
  const HorizontalIlluminance e = horizontalIlluminanceBoth(sunAt(60.0f, 180.0f), 64, 1);
  std::printf("sky horizontal illuminance, sun at 60 deg: %.0f lx, reference %.0f lx (%+.1f %%)\n",
              e.model, e.reference, 100.0 * (e.model / e.reference - 1.0));
  EXPECT_NEAR(e.model / e.reference, 1.0, 0.10);
}
