// A Monte Carlo reference for the sky: a spectral volumetric path tracer in the spherical
// atmosphere, written apart from the tables and the multiple-scattering approximation of
// sky.cpp (it shares only the coefficients, the density profiles and the phase functions).
// Free paths by delta tracking (Woodcock et al. 1965) against a majorant of the extinction,
// scattering weighted by the single-scattering albedo, next-event estimation of the sun with its
// transmittance integrated along the shadow ray by fine quadrature, phase sampling (Rayleigh by
// inversion, Cornette-Shanks through Henyey-Greenstein with the ratio as weight), a Lambertian
// ground, Russian roulette after three orders.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <glm/geometric.hpp>

#include "ibl/env/sky.hpp"
#include "ibl/shared/sky.h"

namespace ibl {

namespace {

constexpr double kPi = std::numbers::pi;

struct Medium {
  shared::AtmosphereShape shape;
  double rayleigh = 0, mieScattering = 0, mieExtinction = 0, ozone = 0;  // one band

  // Scattering (Rayleigh, Mie) and extinction at point p (planet-centered).
  glm::dvec3 at(glm::dvec3 p) const {
    const glm::vec3 d = shared::constituentDensities(
        shape, static_cast<float>(glm::length(p) - shape.bottomRadius));
    const double r = rayleigh * d.x, m = mieScattering * d.y;
    return {r, m, r + mieExtinction * d.y + ozone * d.z};
  }
  double majorant() const { return rayleigh + mieExtinction + ozone; }
};

// Distance along unit `d` from p to the sphere of radius `radius` (far root), or to the ground
// (near root) when `ground` and the ray meets it; negative when the ray misses.
double sphereDistance(glm::dvec3 p, glm::dvec3 d, double radius, bool nearRoot) {
  const double b = glm::dot(p, d), c = glm::dot(p, p) - radius * radius;
  const double disc = b * b - c;
  if (disc < 0.0) return -1.0;
  const double s = std::sqrt(disc);
  return nearRoot ? -b - s : -b + s;
}

// Transmittance from p toward unit d to the top of the atmosphere: 0 through the ground, else
// exp(-optical depth) by the midpoint rule on 400 steps crowded near p.
double transmittanceToTop(const Medium& m, glm::dvec3 p, glm::dvec3 d) {
  const double toGround = sphereDistance(p, d, m.shape.bottomRadius, true);
  if (toGround > 0.0) return 0.0;
  const double length = sphereDistance(p, d, m.shape.topRadius, false);
  constexpr int kSteps = 400;
  double depth = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double s0 = static_cast<double>(i) / kSteps, s1 = static_cast<double>(i + 1) / kSteps;
    const double t = length * 0.5 * (s0 * s0 + s1 * s1), dt = length * (s1 * s1 - s0 * s0);
    depth += m.at(p + t * d).z * dt;
  }
  return std::exp(-depth);
}

// An orthonormal frame around unit n, and a direction with cosine `c` and azimuth `phi` in it.
glm::dvec3 around(glm::dvec3 n, double c, double phi) {
  const glm::dvec3 a = std::abs(n.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(a, n)), v = glm::cross(n, u);
  const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
  return s * std::cos(phi) * u + s * std::sin(phi) * v + c * n;
}

// The radiance of one band toward the observer at `origin` from direction `view`, per unit
// solar irradiance, from `paths` paths.
double traceBand(const Medium& m, glm::dvec3 origin, glm::dvec3 view, glm::dvec3 sun, float g,
                 float albedo, int paths, int orders, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  double sum = 0.0;
  for (int k = 0; k < paths; ++k) {
    glm::dvec3 p = origin, d = view;
    double throughput = 1.0, l = 0.0;
    for (int order = 0; order < orders; ++order) {
      const double toGround = sphereDistance(p, d, m.shape.bottomRadius, true);
      const bool ground = toGround > 1e-6;
      const double end = ground ? toGround : sphereDistance(p, d, m.shape.topRadius, false);
      // Delta tracking: tentative collisions at the majorant's rate, real with probability
      // extinction / majorant.
      double t = 0.0;
      glm::dvec3 coefficients(0.0);
      bool collided = false;
      while (true) {
        t -= std::log(1.0 - uniform(rng)) / m.majorant();
        if (t >= end) break;
        coefficients = m.at(p + t * d);
        if (uniform(rng) * m.majorant() < coefficients.z) {
          collided = true;
          break;
        }
      }
      if (!collided && !ground) break;  // into space
      if (collided) {
        p += t * d;
        const double scattering = coefficients.x + coefficients.y;
        throughput *= scattering / coefficients.z;
        // The sun, with the medium's phase function (the two constituents' mixture).
        const double cosSun = glm::dot(d, sun);
        const double phase =
            (coefficients.x * shared::rayleighPhase(static_cast<float>(cosSun)) +
             coefficients.y * shared::cornetteShanksPhase(static_cast<float>(cosSun), g)) /
            scattering;
        l += throughput * phase * transmittanceToTop(m, p, sun);
        // The next direction from one constituent's phase function.
        if (uniform(rng) * scattering < coefficients.x) {
          // Rayleigh by inversion of its CDF in mu: mu^3 + 3 mu = 4 (2u - 1) (Cardano).
          const double q = 4.0 * (2.0 * uniform(rng) - 1.0);
          const double a = std::cbrt(q / 2.0 + std::sqrt(q * q / 4.0 + 1.0));
          d = around(d, a - 1.0 / a, 2.0 * kPi * uniform(rng));
        } else {
          // Henyey-Greenstein with g, then the Cornette-Shanks / HG ratio as weight.
          const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * uniform(rng));
          const double mu = std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
          const double hg = (1.0 - g * g) / (4.0 * kPi * std::pow(1.0 + g * g - 2.0 * g * mu, 1.5));
          throughput *= shared::cornetteShanksPhase(static_cast<float>(mu), g) / hg;
          d = around(d, mu, 2.0 * kPi * uniform(rng));
        }
      } else {
        // The ground: Lambertian, the sun by next-event estimation, the next direction
        // cosine-distributed (weight: the albedo).
        p += toGround * d;
        const glm::dvec3 n = glm::normalize(p);
        p = n * (m.shape.bottomRadius + 1e-3);
        l += throughput * albedo / kPi * std::max(glm::dot(n, sun), 0.0) *
             transmittanceToTop(m, p, sun);
        throughput *= albedo;
        d = around(n, std::sqrt(uniform(rng)), 2.0 * kPi * uniform(rng));
      }
      if (throughput <= 0.0) break;
      if (order >= 3) {  // Russian roulette
        const double q = std::min(throughput, 0.95);
        if (uniform(rng) >= q) break;
        throughput /= q;
      }
    }
    sum += l;
  }
  return sum / paths;
}

}  // namespace

Spectrum pathTracedSkyRadiance(const SkyParameters& p, glm::vec3 direction, int paths,
                               unsigned seed, int orders) {
  const AtmosphereCoefficients c = atmosphereCoefficients(p);
  Medium base;
  base.shape = skyAtmosphereShape();
  const glm::dvec3 origin(0.0, base.shape.bottomRadius + std::max(p.altitude, 0.0f) + 1e-3, 0.0);
  const glm::dvec3 sun(sunDirection(p.sunElevation, p.sunAzimuth));
  const glm::dvec3 view = glm::normalize(glm::dvec3(direction));
  Spectrum out{};
  // Band after band (a measuring tool: simple and reproducible rather than fast).
  for (int band = 0; band < kSkyBands; ++band) {
    Medium m = base;
    m.rayleigh = c.rayleighScattering[band];
    m.mieScattering = c.mieScattering[band];
    m.mieExtinction = c.mieExtinction[band];
    m.ozone = c.ozoneAbsorption[band];
    std::mt19937_64 rng(seed * 1000003ull + static_cast<unsigned>(band));
    out[band] = static_cast<float>(
        traceBand(m, origin, view, sun, skyMieAsymmetry(), p.groundAlbedo, paths, orders, rng) *
        solarIrradianceAtTop()[band]);
  }
  return out;
}

}  // namespace ibl
