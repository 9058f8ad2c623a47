#include "ibl/env/sky.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/env/equirect.hpp"
#include "ibl/math/color.hpp"
#include "ibl/shared/sky.h"

namespace ibl {

using shared::AtmosphereShape;
using shared::constituentDensities;
using shared::distanceToGround;
using shared::distanceToSphereFar;
using shared::radiusAndCosineAfter;
using shared::rayMeetsGround;

namespace {

constexpr double kPi = std::numbers::pi;

// Physical constants (CODATA 2018) and the standard atmosphere at sea level (ISO 2533).
constexpr double kPlanck = 6.62607015e-34;       // J s
constexpr double kLightSpeed = 299792458.0;      // m/s
constexpr double kBoltzmann = 1.380649e-23;      // J/K
constexpr double kSeaLevelTemperature = 288.15;  // K
constexpr double kSeaLevelPressure = 101325.0;   // Pa
constexpr double kAirMolarMass = 28.9647e-3;     // kg/mol
constexpr double kAvogadro = 6.02214076e23;      // 1/mol
constexpr double kGravity = 9.80665;             // m/s^2
constexpr double kLuminousEfficacy = 683.0;      // lm/W at 555 nm
// The Sun (IAU 2015 resolution B3 nominal values) and the astronomical unit.
constexpr double kSunTemperature = 5772.0;  // K, effective
constexpr double kSunRadius = 6.957e8;      // m
constexpr double kAstronomicalUnit = 1.495978707e11;
constexpr double kSunAngularDiameter = 2.0 * 0.26656 * kPi / 180.0;  // 0.533 degrees at 1 au
constexpr double kDobson = 2.6867e20;  // molecules per m^2 in one Dobson unit

// Aerosols (a continental clear sky): Angstrom exponent, single-scattering albedo, asymmetry.
constexpr double kAngstromExponent = 1.3;
constexpr double kAerosolAlbedo = 0.9;
constexpr float kMieAsymmetry = 0.8f;
// Linear limb darkening of the solar disk, I(mu) = I(1) (1 - u (1 - mu)) (u ~ 0.6 in the
// visible: Neckel & Labs 1994).
constexpr double kLimbDarkening = 0.6;

// The planet: Earth's mean radius, an atmosphere 100 km thick, the scale heights of an
// isothermal atmosphere at 288.15 K (k T / (m g) = 8.43 km) and of continental aerosols
// (1.2 km), ozone in a tent from 10 to 40 km (Bruneton 2017).
AtmosphereShape earth() {
  AtmosphereShape a;
  a.bottomRadius = 6371.0e3f;
  a.topRadius = 6471.0e3f;
  a.rayleighHeight = static_cast<float>(kBoltzmann * kSeaLevelTemperature /
                                        (kAirMolarMass / kAvogadro * kGravity));
  a.mieHeight = 1200.0f;
  a.ozoneCenter = 25.0e3f;
  a.ozoneHalfWidth = 15.0e3f;
  return a;
}

// Ozone's absorption cross-section, m^2 per molecule, at 390, 410, ... 770 nm (Serdyuchenko et
// al. 2014, "High spectral resolution ozone absorption cross-sections", 293 K: the Chappuis
// band).
constexpr std::array<double, kSkyBands> kOzoneCrossSection = {
    6.636e-28, 2.763e-27, 8.451e-27, 2.316e-26, 4.924e-26, 9.016e-26, 1.602e-25,
    2.755e-25, 3.500e-25, 4.672e-25, 4.701e-25, 4.305e-25, 3.215e-25, 2.238e-25,
    1.473e-25, 9.423e-26, 6.566e-26, 4.150e-26, 3.237e-26, 2.801e-26};

// The refractive index of standard air at `lambdaNm` (Peck & Reeder 1972, eq. 2).
double airRefractiveIndex(double lambdaNm) {
  const double s2 = 1.0 / (lambdaNm * 1e-3 * lambdaNm * 1e-3);  // (1/um)^2
  return 1.0 + 1e-8 * (8060.51 + 2480990.0 / (132.274 - s2) + 17455.7 / (39.32957 - s2));
}

// The Rayleigh scattering coefficient of sea-level air, m^-1: N sigma, with the cross-section
// sigma = 24 pi^3 / (lambda^4 N^2) ((n^2 - 1) / (n^2 + 2))^2 (6 + 3 delta) / (6 - 7 delta)
// (Bucholtz 1995, eq. 2; depolarization delta = 0.0279, Young 1980).
double rayleighCoefficient(double lambdaNm) {
  const double n = airRefractiveIndex(lambdaNm), n2 = n * n;
  const double number = kSeaLevelPressure / (kBoltzmann * kSeaLevelTemperature);  // m^-3
  const double lambda = lambdaNm * 1e-9;
  constexpr double delta = 0.0279;
  const double lorentz = (n2 - 1.0) / (n2 + 2.0);
  const double sigma = 24.0 * kPi * kPi * kPi / (std::pow(lambda, 4.0) * number * number) *
                       lorentz * lorentz * (6.0 + 3.0 * delta) / (6.0 - 7.0 * delta);
  return number * sigma;
}

// Planck's spectral radiance of a blackbody, W m^-2 sr^-1 nm^-1.
double planck(double lambdaNm, double kelvin) {
  const double lambda = lambdaNm * 1e-9;
  const double b = 2.0 * kPlanck * kLightSpeed * kLightSpeed / std::pow(lambda, 5.0) /
                   std::expm1(kPlanck * kLightSpeed / (lambda * kBoltzmann * kelvin));
  return b * 1e-9;
}

// Texel-centered table coordinates: x in [0, 1] to a continuous index in [0, n - 1].
float tableIndex(float x, int n) {
  return std::clamp(x, 0.0f, 1.0f) * static_cast<float>(n - 1);
}

}  // namespace

AtmosphereShape skyAtmosphereShape() {
  return earth();
}
float skyMieAsymmetry() {
  return kMieAsymmetry;
}

glm::vec3 sunDirection(float elevationDegrees, float azimuthDegrees) {
  const float e = glm::radians(elevationDegrees), a = glm::radians(azimuthDegrees);
  return {std::cos(e) * std::sin(a), std::sin(e), -std::cos(e) * std::cos(a)};
}

void checkSkyParameters(const SkyParameters& p, std::string_view what) {
  const auto check = [&](float v, float lo, float hi, const char* name) {
    if (!(v >= lo && v <= hi))
      fail(what, fmt::format("{} must be in [{}, {}], not {}", name, lo, hi, v));
  };
  check(p.sunElevation, -90.0f, 90.0f, "the sun's elevation");
  check(p.sunAzimuth, -360.0f, 360.0f, "the sun's azimuth");
  check(p.altitude, 0.0f, 80000.0f, "the altitude (m)");
  check(p.turbidity, 1.0f, 20.0f, "the turbidity");
  check(p.ozone, 0.0f, 1000.0f, "the ozone column (Dobson units)");
  check(p.groundAlbedo, 0.0f, 1.0f, "the ground albedo");
}

AtmosphereCoefficients atmosphereCoefficients(const SkyParameters& p) {
  const AtmosphereShape shape = earth();
  AtmosphereCoefficients c;
  // Turbidity as the ratio of the total optical depth to the molecules' at 550 nm: the aerosols'
  // vertical optical depth is (T - 1) tau_R(550), spread over the aerosol scale height and
  // falling with wavelength by Angstrom's law.
  const double tauRayleigh550 = rayleighCoefficient(550.0) * shape.rayleighHeight;
  const double tauAerosol550 = (p.turbidity - 1.0) * tauRayleigh550;
  const double ozonePeak = p.ozone * kDobson / shape.ozoneHalfWidth;  // molecules m^-3
  for (int i = 0; i < kSkyBands; ++i) {
    const double lambda = skyWavelength(i);
    c.rayleighScattering[i] = static_cast<float>(rayleighCoefficient(lambda));
    const double mie =
        tauAerosol550 / shape.mieHeight * std::pow(lambda / 550.0, -kAngstromExponent);
    c.mieExtinction[i] = static_cast<float>(mie);
    c.mieScattering[i] = static_cast<float>(mie * kAerosolAlbedo);
    c.ozoneAbsorption[i] = static_cast<float>(ozonePeak * kOzoneCrossSection[i]);
  }
  return c;
}

const Spectrum& solarIrradianceAtTop() {
  static const Spectrum e = [] {
    Spectrum s{};
    const double dilution =
        kPi * (kSunRadius / kAstronomicalUnit) * (kSunRadius / kAstronomicalUnit);
    for (int i = 0; i < kSkyBands; ++i)
      s[i] = static_cast<float>(dilution * planck(skyWavelength(i), kSunTemperature));
    return s;
  }();
  return e;
}

glm::vec3 spectrumToXyz(const Spectrum& s) {
  glm::dvec3 xyz(0.0);
  for (int i = 0; i < kSkyBands; ++i)
    xyz += static_cast<double>(s[i]) * colorMatching(skyWavelength(i));
  return glm::vec3(xyz * (kLuminousEfficacy * kSkyBandWidth));
}

// ---------------------------------------------------------------------------------------------
// The tables. Optical depth: the column densities of the three constituents (relative to their
// reference densities) from (r, mu) to the top of the atmosphere, for rays that miss the ground,
// in Bruneton's parameterization (Bruneton 2017, functions GetTransmittanceTextureUvFromRMu and
// its inverse). Multiple scattering: Hillaire 2020's Psi_ms(r, mu_s), per band.

struct SkyModel::Tables {
  AtmosphereShape shape = earth();
  AtmosphereCoefficients coefficients;
  Spectrum top{};  // solar irradiance at the top of the atmosphere
  float observerRadius = 0.0f;
  glm::vec3 sun{0.0f, 1.0f, 0.0f};

  static constexpr int kDepthMu = 256, kDepthR = 64;
  std::vector<glm::vec3> depth;  // [r][mu]
  static constexpr int kMsMu = 32, kMsR = 32;
  std::vector<Spectrum> multiple;  // [r][mu_s], per unit solar irradiance
  Spectrum groundSky{};            // sky irradiance on the ground, per unit solar irradiance

  float horizonDistance() const {
    return std::sqrt(shape.topRadius * shape.topRadius - shape.bottomRadius * shape.bottomRadius);
  }

  glm::vec3 integrateDepth(float r, float mu) const {
    const float length = distanceToSphereFar(r, mu, shape.topRadius);
    constexpr int kSteps = 256;
    glm::dvec3 sum(0.0);
    // Quadratic spacing: short steps near the start, where the density changes fastest.
    for (int i = 0; i < kSteps; ++i) {
      const float s0 = static_cast<float>(i) / kSteps, s1 = static_cast<float>(i + 1) / kSteps;
      const float t = length * 0.5f * (s0 * s0 + s1 * s1);
      const float dt = length * (s1 * s1 - s0 * s0);
      const float h = radiusAndCosineAfter(r, mu, t).x - shape.bottomRadius;
      sum += glm::dvec3(constituentDensities(shape, h)) * static_cast<double>(dt);
    }
    return glm::vec3(sum);
  }

  void buildDepth() {
    depth.resize(static_cast<std::size_t>(kDepthMu) * kDepthR);
    const float H = horizonDistance();
    parallelFor(0, kDepthR, [&](int j) {
      const float rho = H * static_cast<float>(j) / (kDepthR - 1);
      const float r = std::sqrt(rho * rho + shape.bottomRadius * shape.bottomRadius);
      for (int i = 0; i < kDepthMu; ++i) {
        const float dMin = shape.topRadius - r, dMax = rho + H;
        const float d = dMin + static_cast<float>(i) / (kDepthMu - 1) * (dMax - dMin);
        const float mu =
            d == 0.0f ? 1.0f
                      : std::clamp((H * H - rho * rho - d * d) / (2.0f * r * d), -1.0f, 1.0f);
        depth[static_cast<std::size_t>(j) * kDepthMu + i] = integrateDepth(r, mu);
      }
    });
  }

  // Column densities from (r, mu) to the top; the ray must miss the ground.
  glm::vec3 columnDensities(float r, float mu) const {
    const float H = horizonDistance();
    const float rho = std::sqrt(std::max(r * r - shape.bottomRadius * shape.bottomRadius, 0.0f));
    const float d = distanceToSphereFar(r, mu, shape.topRadius);
    const float dMin = shape.topRadius - r, dMax = rho + H;
    const float x = tableIndex(dMax > dMin ? (d - dMin) / (dMax - dMin) : 0.0f, kDepthMu);
    const float y = tableIndex(rho / H, kDepthR);
    const int x0 = std::min(static_cast<int>(x), kDepthMu - 2);
    const int y0 = std::min(static_cast<int>(y), kDepthR - 2);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    const auto at = [&](int yy, int xx) {
      return depth[static_cast<std::size_t>(yy) * kDepthMu + xx];
    };
    return glm::mix(glm::mix(at(y0, x0), at(y0, x0 + 1), fx),
                    glm::mix(at(y0 + 1, x0), at(y0 + 1, x0 + 1), fx), fy);
  }

  // The transmittance to the top from (r, mu), per band; 0 through the ground.
  Spectrum transmittanceToTop(float r, float mu) const {
    Spectrum t{};
    if (rayMeetsGround(r, mu, shape.bottomRadius)) return t;
    const glm::vec3 c = columnDensities(r, mu);
    for (int i = 0; i < kSkyBands; ++i)
      t[i] =
          std::exp(-(coefficients.rayleighScattering[i] * c.x +
                     coefficients.mieExtinction[i] * c.y + coefficients.ozoneAbsorption[i] * c.z));
    return t;
  }

  Spectrum multipleAt(float r, float muS) const {
    const float x = tableIndex(0.5f + 0.5f * muS, kMsMu);
    const float y =
        tableIndex((r - shape.bottomRadius) / (shape.topRadius - shape.bottomRadius), kMsR);
    const int x0 = std::min(static_cast<int>(x), kMsMu - 2);
    const int y0 = std::min(static_cast<int>(y), kMsR - 2);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    const auto& a = multiple[static_cast<std::size_t>(y0) * kMsMu + x0];
    const auto& b = multiple[static_cast<std::size_t>(y0) * kMsMu + x0 + 1];
    const auto& c = multiple[static_cast<std::size_t>(y0 + 1) * kMsMu + x0];
    const auto& d = multiple[static_cast<std::size_t>(y0 + 1) * kMsMu + x0 + 1];
    Spectrum s;
    for (int i = 0; i < kSkyBands; ++i)
      s[i] = (1.0f - fy) * ((1.0f - fx) * a[i] + fx * b[i]) + fy * ((1.0f - fx) * c[i] + fx * d[i]);
    return s;
  }

  // Hillaire 2020, section 5.5: from a point at radius r with the sun at zenith cosine muS, the
  // second-order light L2 (single scattering with an isotropic phase, and the lit ground, seen
  // over the whole sphere) and the transfer f_ms of isotropic light to the point; the infinite
  // series of orders is L2 / (1 - f_ms) (eq. 9).
  Spectrum multipleScatteringAt(float r, float muS, float albedo) const {
    constexpr int kDirections = 8;  // 8 x 8 stratified over the sphere
    constexpr int kSteps = 20;
    Spectrum l2{}, fms{};
    const glm::vec3 sunDir(std::sqrt(std::max(1.0f - muS * muS, 0.0f)), muS, 0.0f);
    for (int a = 0; a < kDirections; ++a)
      for (int b = 0; b < kDirections; ++b) {
        const float cosTheta = 1.0f - 2.0f * (static_cast<float>(a) + 0.5f) / kDirections;
        const float phi =
            2.0f * static_cast<float>(kPi) * (static_cast<float>(b) + 0.5f) / kDirections;
        const float sinTheta = std::sqrt(std::max(1.0f - cosTheta * cosTheta, 0.0f));
        const glm::vec3 d(sinTheta * std::cos(phi), cosTheta, sinTheta * std::sin(phi));
        const float mu = d.y, nu = glm::dot(d, sunDir);
        const bool ground = rayMeetsGround(r, mu, shape.bottomRadius);
        const float length = ground ? distanceToGround(r, mu, shape.bottomRadius)
                                    : distanceToSphereFar(r, mu, shape.topRadius);
        Spectrum throughput;
        throughput.fill(1.0f);
        const float dt = length / kSteps;
        for (int s = 0; s < kSteps; ++s) {
          const float t = (static_cast<float>(s) + 0.5f) * dt;
          const glm::vec2 rm = radiusAndCosineAfter(r, mu, t);
          const float muSt = std::clamp((r * muS + t * nu) / rm.x, -1.0f, 1.0f);
          const glm::vec3 rho = constituentDensities(shape, rm.x - shape.bottomRadius);
          const Spectrum sunT = transmittanceToTop(rm.x, muSt);
          for (int i = 0; i < kSkyBands; ++i) {
            const float scattering =
                coefficients.rayleighScattering[i] * rho.x + coefficients.mieScattering[i] * rho.y;
            const float extinction = coefficients.rayleighScattering[i] * rho.x +
                                     coefficients.mieExtinction[i] * rho.y +
                                     coefficients.ozoneAbsorption[i] * rho.z;
            const float stepT = std::exp(-extinction * dt);
            const float integral = extinction > 0.0f ? (1.0f - stepT) / extinction : dt;
            const float isotropic = 1.0f / (4.0f * static_cast<float>(kPi));
            l2[i] += throughput[i] * scattering * integral * sunT[i] * isotropic;
            fms[i] += throughput[i] * scattering * integral;
            throughput[i] *= stepT;
          }
        }
        if (ground && albedo > 0.0f) {
          const glm::vec2 rm = radiusAndCosineAfter(r, mu, length);
          const float muSg = std::clamp((r * muS + length * nu) / rm.x, -1.0f, 1.0f);
          const Spectrum sunT = transmittanceToTop(shape.bottomRadius, muSg);
          for (int i = 0; i < kSkyBands; ++i)
            l2[i] +=
                throughput[i] * sunT[i] * std::max(muSg, 0.0f) * albedo / static_cast<float>(kPi);
        }
      }
    // Uniform directions over the sphere: the mean over them is the integral against the
    // isotropic phase function 1 / (4 pi) (eq. 7 and 8).
    const float n = kDirections * kDirections;
    Spectrum psi;
    for (int i = 0; i < kSkyBands; ++i)
      psi[i] = (l2[i] / n) / (1.0f - std::min(fms[i] / n, 0.999f));
    return psi;
  }

  void buildMultiple(float albedo, bool enabled) {
    multiple.assign(static_cast<std::size_t>(kMsMu) * kMsR, Spectrum{});
    if (!enabled) return;
    parallelFor(0, kMsR * kMsMu, [&](int k) {
      const int j = k / kMsMu, i = k % kMsMu;
      const float r = shape.bottomRadius + (shape.topRadius - shape.bottomRadius) *
                                               std::max(static_cast<float>(j) / (kMsR - 1), 1e-4f);
      const float muS = -1.0f + 2.0f * static_cast<float>(i) / (kMsMu - 1);
      multiple[static_cast<std::size_t>(k)] = multipleScatteringAt(r, muS, albedo);
    });
  }

  // In-scattered radiance toward a point at radius r0 from direction d (zenith +Y), per unit
  // solar irradiance, and where the ray meets the ground, the ground's reflection.
  Spectrum inscattered(float r0, glm::vec3 d, float albedo, bool withGround) const {
    const float mu = d.y, muS = sun.y, nu = glm::dot(d, sun);
    const bool ground = rayMeetsGround(r0, mu, shape.bottomRadius);
    const float length = ground ? distanceToGround(r0, mu, shape.bottomRadius)
                                : distanceToSphereFar(r0, mu, shape.topRadius);
    const float phaseR = shared::rayleighPhase(nu);
    const float phaseM = shared::cornetteShanksPhase(nu, kMieAsymmetry);
    Spectrum l{}, throughput;
    throughput.fill(1.0f);
    constexpr int kSteps = 40;
    for (int s = 0; s < kSteps && length > 0.0f; ++s) {
      const float s0 = static_cast<float>(s) / kSteps, s1 = static_cast<float>(s + 1) / kSteps;
      const float t = length * 0.5f * (s0 * s0 + s1 * s1);
      const float dt = length * (s1 * s1 - s0 * s0);
      const glm::vec2 rm = radiusAndCosineAfter(r0, mu, t);
      const float muSt = std::clamp((r0 * muS + t * nu) / rm.x, -1.0f, 1.0f);
      const glm::vec3 rho = constituentDensities(shape, rm.x - shape.bottomRadius);
      const Spectrum sunT = transmittanceToTop(rm.x, muSt);
      const Spectrum psi = multipleAt(rm.x, muSt);
      for (int i = 0; i < kSkyBands; ++i) {
        const float rayleigh = coefficients.rayleighScattering[i] * rho.x;
        const float mie = coefficients.mieScattering[i] * rho.y;
        const float extinction = rayleigh + coefficients.mieExtinction[i] * rho.y +
                                 coefficients.ozoneAbsorption[i] * rho.z;
        const float source =
            rayleigh * (phaseR * sunT[i] + psi[i]) + mie * (phaseM * sunT[i] + psi[i]);
        const float stepT = std::exp(-extinction * dt);
        // The source's integral over the step with the step's own attenuation (Hillaire 2020,
        // eq. 6 note: energy-conserving integration).
        const float integral = extinction > 0.0f ? (1.0f - stepT) / extinction : dt;
        l[i] += throughput[i] * source * integral;
        throughput[i] *= stepT;
      }
    }
    if (ground && withGround && albedo > 0.0f) {
      const glm::vec2 rm = radiusAndCosineAfter(r0, mu, length);
      const float muSg = std::clamp((r0 * muS + length * nu) / rm.x, -1.0f, 1.0f);
      const Spectrum sunT = transmittanceToTop(shape.bottomRadius, muSg);
      for (int i = 0; i < kSkyBands; ++i)
        l[i] += throughput[i] * albedo / static_cast<float>(kPi) *
                (sunT[i] * std::max(muSg, 0.0f) + groundSky[i]);
    }
    return l;
  }

  // The sky's irradiance on a horizontal patch of ground, per unit solar irradiance (a 32 x 64
  // midpoint quadrature over the upper hemisphere).
  void buildGroundSky() {
    groundSky.fill(0.0f);
    constexpr int kTheta = 32, kPhi = 64;
    std::vector<Spectrum> rows(kTheta);
    parallelFor(0, kTheta, [&](int a) {
      Spectrum row{};
      const double t0 = 0.5 * kPi * a / kTheta, t1 = 0.5 * kPi * (a + 1) / kTheta;
      const float theta = static_cast<float>(0.5 * (t0 + t1));
      // The integral of cos(theta) over the ring, divided among its cells.
      const float weight = static_cast<float>(0.5 * (std::cos(2.0 * t0) - std::cos(2.0 * t1)) *
                                              0.5 * 2.0 * kPi / kPhi);
      for (int b = 0; b < kPhi; ++b) {
        const float phi = static_cast<float>(2.0 * kPi * (b + 0.5) / kPhi);
        const glm::vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                          std::sin(theta) * std::sin(phi));
        const Spectrum l = inscattered(shape.bottomRadius, d, 0.0f, false);
        for (int i = 0; i < kSkyBands; ++i) row[i] += l[i] * weight;
      }
      rows[static_cast<std::size_t>(a)] = row;
    });
    for (const Spectrum& row : rows)
      for (int i = 0; i < kSkyBands; ++i) groundSky[i] += row[i];
  }

  // The sky-view table (after Hillaire 2020, section 5.3): the sky's radiance as linear Rec.709
  // over the view's azimuth from the sun's (0 to pi: the sky is symmetric about the sun's
  // vertical plane) and its elevation, in two halves that meet at the horizon (the ground's edge
  // is a discontinuity no interpolation may cross), each with rows crowded toward the horizon
  // (elevation from it proportional to the square of the row coordinate).
  static constexpr int kViewAzimuths = 256, kViewRows = 160;  // rows per half
  std::vector<glm::vec3> skyView;                             // [half][row][azimuth]
  std::once_flag skyViewBuilt;                                // by the first panorama
  float horizonElevation = 0.0f;                              // radians, <= 0

  // The elevation (radians) of row j of half `below` (0: above the horizon).
  float viewRowElevation(int below, int j) const {
    const float t = static_cast<float>(j) / (kViewRows - 1);
    const float span = below ? horizonElevation + 0.5f * static_cast<float>(kPi)
                             : 0.5f * static_cast<float>(kPi) - horizonElevation;
    return horizonElevation + (below ? -1.0f : 1.0f) * span * t * t;
  }

  // The direction at elevation e and azimuth a from the sun's.
  glm::vec3 viewDirection(float e, float a) const {
    const float sunAzimuth = std::atan2(sun.x, -sun.z);  // compass, from north (-Z) toward +X
    const float compass = sunAzimuth + a;
    return {std::cos(e) * std::sin(compass), std::sin(e), -std::cos(e) * std::cos(compass)};
  }

  void buildSkyView(float albedo) {
    skyView.resize(static_cast<std::size_t>(2) * kViewRows * kViewAzimuths);
    parallelFor(0, 2 * kViewRows, [&](int row) {
      const int below = row / kViewRows, j = row % kViewRows;
      // The horizon rows sit just on their side of it.
      const float e = viewRowElevation(below, j) + (j == 0 ? (below ? -1e-5f : 1e-5f) : 0.0f);
      for (int i = 0; i < kViewAzimuths; ++i) {
        const float a = static_cast<float>(kPi) * static_cast<float>(i) / (kViewAzimuths - 1);
        Spectrum l = inscattered(observerRadius, viewDirection(e, a), albedo, true);
        for (int k = 0; k < kSkyBands; ++k) l[k] *= top[k];
        skyView[static_cast<std::size_t>(row) * kViewAzimuths + i] =
            glm::max(xyzToLinearRec709(spectrumToXyz(l)), glm::vec3(0.0f));
      }
    });
  }

  glm::vec3 skyViewAt(glm::vec3 d) const {
    const float e = std::asin(std::clamp(d.y, -1.0f, 1.0f));
    const int below = e < horizonElevation ? 1 : 0;
    const float span = below ? horizonElevation + 0.5f * static_cast<float>(kPi)
                             : 0.5f * static_cast<float>(kPi) - horizonElevation;
    const float y = tableIndex(
        span > 0.0f ? std::sqrt(std::abs(e - horizonElevation) / span) : 0.0f, kViewRows);
    const float sunAzimuth = std::atan2(sun.x, -sun.z);
    float a = std::abs(std::atan2(d.x, -d.z) - sunAzimuth);
    if (a > static_cast<float>(kPi)) a = 2.0f * static_cast<float>(kPi) - a;
    const float x = tableIndex(a / static_cast<float>(kPi), kViewAzimuths);
    const int x0 = std::min(static_cast<int>(x), kViewAzimuths - 2);
    const int y0 = std::min(static_cast<int>(y), kViewRows - 2);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    const auto at = [&](int yy, int xx) {
      return skyView[(static_cast<std::size_t>(below) * kViewRows + yy) * kViewAzimuths + xx];
    };
    return glm::mix(glm::mix(at(y0, x0), at(y0, x0 + 1), fx),
                    glm::mix(at(y0 + 1, x0), at(y0 + 1, x0 + 1), fx), fy);
  }
};

SkyModel::SkyModel(const SkyParameters& p) : params_(p), tables_(std::make_unique<Tables>()) {
  checkSkyParameters(p, "sky");
  Tables& t = *tables_;
  t.coefficients = atmosphereCoefficients(p);
  t.top = solarIrradianceAtTop();
  t.observerRadius = t.shape.bottomRadius + std::max(p.altitude, 0.0f);
  t.sun = ibl::sunDirection(p.sunElevation, p.sunAzimuth);
  t.buildDepth();
  t.buildMultiple(p.groundAlbedo, p.multipleScattering);
  if (p.groundAlbedo > 0.0f) t.buildGroundSky();
  t.horizonElevation = -std::acos(std::min(t.shape.bottomRadius / t.observerRadius, 1.0f));
}

SkyModel::~SkyModel() = default;
SkyModel::SkyModel(SkyModel&&) noexcept = default;
SkyModel& SkyModel::operator=(SkyModel&&) noexcept = default;

const SkyParameters& SkyModel::parameters() const {
  return params_;
}
glm::vec3 SkyModel::sunDirection() const {
  return tables_->sun;
}

Spectrum SkyModel::transmittance(glm::vec3 d) const {
  return tables_->transmittanceToTop(tables_->observerRadius, glm::normalize(d).y);
}

Spectrum SkyModel::radiance(glm::vec3 d) const {
  const Tables& t = *tables_;
  Spectrum l = t.inscattered(t.observerRadius, glm::normalize(d), params_.groundAlbedo, true);
  for (int i = 0; i < kSkyBands; ++i) l[i] *= t.top[i];
  return l;
}

Light SkyModel::sun() const {
  const Tables& t = *tables_;
  Spectrum e = t.transmittanceToTop(t.observerRadius, t.sun.y);
  for (int i = 0; i < kSkyBands; ++i) e[i] *= t.top[i];
  const glm::vec3 xyz = spectrumToXyz(e);
  Light light;
  light.type = LightType::Sun;
  light.name = "sky: sun";
  light.direction = t.sun;
  light.angularDiameter = static_cast<float>(kSunAngularDiameter);
  light.intensity = std::max(xyz.y, 0.0f);
  const glm::vec3 rgb = xyzToLinearRec709(xyz);
  light.color = xyz.y > 0.0f ? rgb / xyz.y : glm::vec3(1.0f);
  return light;
}

Image SkyModel::panorama(int width, int height, bool paintSun) const {
  if (width < 2 || height < 1 || width > 16384 || height > 8192)
    fail("sky", fmt::format("panorama size {}x{} out of range", width, height));
  std::call_once(tables_->skyViewBuilt, [&] { tables_->buildSkyView(params_.groundAlbedo); });
  Image image(width, height);
  const float w = static_cast<float>(width), h = static_cast<float>(height);
  parallelFor(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const glm::vec3 d = equirectToDirection((static_cast<float>(x) + 0.5f) / w,
                                              (static_cast<float>(y) + 0.5f) / h);
      image.at(x, y) = tables_->skyViewAt(d);
    }
  });
  if (!paintSun) return image;
  const Light s = sun();
  if (s.intensity <= 0.0f) return image;
  // The disk, limb-darkened, supersampled 16 x 16 per pixel near it, then scaled so that the
  // pixels' radiance times their solid angle adds up to the sun's illuminance exactly.
  const double radius = 0.5 * kSunAngularDiameter;
  const glm::vec2 c = directionToEquirect(s.direction);
  const int cy = static_cast<int>(c.y * h);
  const double pixelAngle = kPi / height;
  const int reachY = static_cast<int>(std::ceil(radius / pixelAngle)) + 2;
  std::vector<std::pair<std::size_t, double>> covered;  // pixel, relative radiance
  double weighted = 0.0;                                // sum of relative radiance x solid angle
  constexpr int kSub = 16;
  for (int y = std::max(cy - reachY, 0); y <= std::min(cy + reachY, height - 1); ++y) {
    const float sinTheta =
        std::max(std::sin((static_cast<float>(y) + 0.5f) / h * static_cast<float>(kPi)), 1e-4f);
    const int reachX =
        std::min(width / 2, static_cast<int>(static_cast<float>(reachY) / sinTheta) + 2);
    const int cx = static_cast<int>(c.x * w);
    for (int xx = cx - reachX; xx <= cx + reachX; ++xx) {
      const int x = ((xx % width) + width) % width;
      double sum = 0.0;
      for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b) {
          const glm::vec3 d = equirectToDirection(
              (static_cast<float>(x) + (static_cast<float>(b) + 0.5f) / kSub) / w,
              (static_cast<float>(y) + (static_cast<float>(a) + 0.5f) / kSub) / h);
          const double angle =
              std::acos(std::clamp(static_cast<double>(glm::dot(d, s.direction)), -1.0, 1.0));
          if (angle >= radius) continue;
          const double rr = angle / radius;
          sum += 1.0 - kLimbDarkening * (1.0 - std::sqrt(1.0 - rr * rr));
        }
      if (sum <= 0.0) continue;
      const double relative = sum / (kSub * kSub);
      covered.emplace_back(static_cast<std::size_t>(y) * width + x, relative);
      weighted += relative * equirectPixelSolidAngle(y, width, height);
    }
  }
  if (weighted <= 0.0) return image;
  const glm::vec3 irradiance = s.color * s.intensity;  // Rec.709 "lux" per channel
  for (const auto& [index, relative] : covered)
    image.pixels[index] += irradiance * static_cast<float>(relative / weighted);
  return image;
}

}  // namespace ibl
