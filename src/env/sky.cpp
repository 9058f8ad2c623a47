#include "ibl/env/sky.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
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
using shared::BandCoefficients;
using shared::bandExtinction;
using shared::bandInscatteringSource;
using shared::bandScattering;
using shared::columnDensitiesToTop;
using shared::constituentDensities;
using shared::depthTableCoordinates;
using shared::depthTableRadiusAndCosine;
using shared::distanceToGround;
using shared::distanceToSphereFar;
using shared::groundSkyDirection;
using shared::kDepthTableMu;
using shared::kDepthTableR;
using shared::kGroundSkyRings;
using shared::kGroundSkySectors;
using shared::kMultipleTableMu;
using shared::kMultipleTableR;
using shared::kSkyViewAzimuths;
using shared::kSkyViewRows;
using shared::multipleTableCoordinates;
using shared::multipleTableRadiusAndCosine;
using shared::quadraticStep;
using shared::radiusAndCosineAfter;
using shared::rayMeetsGround;
using shared::skyViewCoordinates;
using shared::skyViewTexelDirection;
using shared::sphereStratumDirection;
using shared::stepIntegral;
using shared::sunCosineAfter;
using shared::tableIndex;

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
      failUsage(what, fmt::format("{} must be from {} to {}, not {}", name, lo, hi, v));
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

glm::dvec3 skyBandXyz(int band) {
  return colorMatching(skyWavelength(band)) * (kLuminousEfficacy * kSkyBandWidth);
}

glm::vec3 spectrumToXyz(const Spectrum& s) {
  glm::dvec3 xyz(0.0);
  for (int i = 0; i < kSkyBands; ++i) xyz += static_cast<double>(s[i]) * skyBandXyz(i);
  return glm::vec3(xyz);
}

// ---------------------------------------------------------------------------------------------
// The tables, with the parameterizations of ibl/shared/sky.h (shaders/env/sky_*.comp build the
// same ones on the GPU). Optical depth: the column densities of the three constituents from
// (r, mu) to the top of the atmosphere, for rays that miss the ground. Multiple scattering:
// Hillaire 2020's Psi_ms(r, mu_s), per band. Sky view: the sky's radiance over directions.

namespace {

std::array<BandCoefficients, kSkyBands> bandCoefficients(const AtmosphereCoefficients& c) {
  std::array<BandCoefficients, kSkyBands> bands{};
  for (int i = 0; i < kSkyBands; ++i)
    bands[i] = {c.rayleighScattering[i], c.mieScattering[i], c.mieExtinction[i],
                c.ozoneAbsorption[i]};
  return bands;
}

// Bilinear interpolation in a row-major table at continuous texel indices (x, y): the four
// texels and their weights.
struct BilinearTap {
  std::size_t i00, i01, i10, i11;  // [y][x]
  float fx, fy;
};
BilinearTap bilinearTap(float x, float y, int width, int height) {
  const int x0 = std::min(static_cast<int>(x), width - 2);
  const int y0 = std::min(static_cast<int>(y), height - 2);
  const std::size_t row = static_cast<std::size_t>(y0) * width;
  return {row + x0,
          row + x0 + 1,
          row + width + x0,
          row + width + x0 + 1,
          x - static_cast<float>(x0),
          y - static_cast<float>(y0)};
}
template <typename T>
T bilinear(const T* table, const BilinearTap& t) {
  return glm::mix(glm::mix(table[t.i00], table[t.i01], t.fx),
                  glm::mix(table[t.i10], table[t.i11], t.fx), t.fy);
}

}  // namespace

struct SkyModel::Tables {
  AtmosphereShape shape = earth();
  std::array<BandCoefficients, kSkyBands> bands{};
  Spectrum top{};  // solar irradiance at the top of the atmosphere
  float observerRadius = 0.0f;
  glm::vec3 sun{0.0f, 1.0f, 0.0f};

  std::vector<glm::vec3> depth;    // [r][mu]
  std::vector<Spectrum> multiple;  // [r][mu_s], per unit solar irradiance
  Spectrum groundSky{};            // sky irradiance on the ground, per unit solar irradiance

  void buildDepth() {
    depth.resize(static_cast<std::size_t>(kDepthTableMu) * kDepthTableR);
    parallelFor(0, kDepthTableR, [&](int j) {
      for (int i = 0; i < kDepthTableMu; ++i) {
        const glm::vec2 rm =
            depthTableRadiusAndCosine(shape, static_cast<float>(i) / (kDepthTableMu - 1),
                                      static_cast<float>(j) / (kDepthTableR - 1));
        depth[static_cast<std::size_t>(j) * kDepthTableMu + i] =
            columnDensitiesToTop(shape, rm.x, rm.y);
      }
    });
  }

  // The transmittance to the top from (r, mu), per band; 0 through the ground.
  Spectrum transmittanceToTop(float r, float mu) const {
    Spectrum t{};
    if (rayMeetsGround(r, mu, shape.bottomRadius)) return t;
    const glm::vec2 xy = depthTableCoordinates(shape, r, mu);
    const glm::vec3 column = bilinear(
        depth.data(), bilinearTap(tableIndex(xy.x, kDepthTableMu), tableIndex(xy.y, kDepthTableR),
                                  kDepthTableMu, kDepthTableR));
    for (int i = 0; i < kSkyBands; ++i) t[i] = std::exp(-bandExtinction(bands[i], column));
    return t;
  }

  Spectrum multipleAt(float r, float muS) const {
    const glm::vec2 xy = multipleTableCoordinates(shape, r, muS);
    const BilinearTap tap =
        bilinearTap(tableIndex(xy.x, kMultipleTableMu), tableIndex(xy.y, kMultipleTableR),
                    kMultipleTableMu, kMultipleTableR);
    Spectrum s;
    const float w00 = (1.0f - tap.fy) * (1.0f - tap.fx), w01 = (1.0f - tap.fy) * tap.fx;
    const float w10 = tap.fy * (1.0f - tap.fx), w11 = tap.fy * tap.fx;
    for (int i = 0; i < kSkyBands; ++i)
      s[i] = w00 * multiple[tap.i00][i] + w01 * multiple[tap.i01][i] + w10 * multiple[tap.i10][i] +
             w11 * multiple[tap.i11][i];
    return s;
  }

  // Hillaire 2020, section 5.5: from a point at radius r with the sun at zenith cosine muS, the
  // second-order light L2 (single scattering with an isotropic phase, and the lit ground, seen
  // over the whole sphere) and the transfer f_ms of isotropic light to the point; the infinite
  // series of orders is L2 / (1 - f_ms) (eq. 9). shaders/env/sky_multiple.comp is its twin.
  Spectrum multipleScatteringAt(float r, float muS, float albedo) const {
    constexpr int kDirections = 8;  // 8 x 8 stratified over the sphere
    constexpr int kSteps = 20;
    Spectrum l2{}, fms{};
    const glm::vec3 sunDir(std::sqrt(std::max(1.0f - muS * muS, 0.0f)), muS, 0.0f);
    for (int a = 0; a < kDirections; ++a)
      for (int b = 0; b < kDirections; ++b) {
        const glm::vec3 d = sphereStratumDirection(a, b, kDirections);
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
          const float muSt = sunCosineAfter(r, muS, nu, t, rm.x);
          const glm::vec3 rho = constituentDensities(shape, rm.x - shape.bottomRadius);
          const Spectrum sunT = transmittanceToTop(rm.x, muSt);
          for (int i = 0; i < kSkyBands; ++i) {
            const float extinction = bandExtinction(bands[i], rho);
            const float stepT = std::exp(-extinction * dt);
            const float scattered =
                throughput[i] * bandScattering(bands[i], rho) * stepIntegral(extinction, dt, stepT);
            l2[i] += scattered * sunT[i] / (4.0f * shared::kPi);  // the isotropic phase function
            fms[i] += scattered;
            throughput[i] *= stepT;
          }
        }
        if (ground && albedo > 0.0f) {
          const glm::vec2 rm = radiusAndCosineAfter(r, mu, length);
          const float muSg = sunCosineAfter(r, muS, nu, length, rm.x);
          const Spectrum sunT = transmittanceToTop(shape.bottomRadius, muSg);
          for (int i = 0; i < kSkyBands; ++i)
            l2[i] += throughput[i] * sunT[i] * std::max(muSg, 0.0f) * albedo / shared::kPi;
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
    multiple.assign(static_cast<std::size_t>(kMultipleTableMu) * kMultipleTableR, Spectrum{});
    if (!enabled) return;
    parallelFor(0, kMultipleTableR * kMultipleTableMu, [&](int k) {
      const int j = k / kMultipleTableMu, i = k % kMultipleTableMu;
      const glm::vec2 rm =
          multipleTableRadiusAndCosine(shape, static_cast<float>(i) / (kMultipleTableMu - 1),
                                       static_cast<float>(j) / (kMultipleTableR - 1));
      multiple[static_cast<std::size_t>(k)] = multipleScatteringAt(rm.x, rm.y, albedo);
    });
  }

  // In-scattered radiance toward a point at radius r0 from direction d (zenith +Y), per unit
  // solar irradiance, and where the ray meets the ground, the ground's reflection.
  // shaders/env/sky_march.glsl is its twin.
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
      const glm::vec2 step = quadraticStep(length, s, kSteps);
      const glm::vec2 rm = radiusAndCosineAfter(r0, mu, step.x);
      const float muSt = sunCosineAfter(r0, muS, nu, step.x, rm.x);
      const glm::vec3 rho = constituentDensities(shape, rm.x - shape.bottomRadius);
      const Spectrum sunT = transmittanceToTop(rm.x, muSt);
      const Spectrum psi = multipleAt(rm.x, muSt);
      for (int i = 0; i < kSkyBands; ++i) {
        const float extinction = bandExtinction(bands[i], rho);
        const float stepT = std::exp(-extinction * step.y);
        l[i] += throughput[i] *
                bandInscatteringSource(bands[i], rho, phaseR, phaseM, sunT[i], psi[i]) *
                stepIntegral(extinction, step.y, stepT);
        throughput[i] *= stepT;
      }
    }
    if (ground && withGround && albedo > 0.0f) {
      const glm::vec2 rm = radiusAndCosineAfter(r0, mu, length);
      const float muSg = sunCosineAfter(r0, muS, nu, length, rm.x);
      const Spectrum sunT = transmittanceToTop(shape.bottomRadius, muSg);
      for (int i = 0; i < kSkyBands; ++i)
        l[i] +=
            throughput[i] * albedo / shared::kPi * (sunT[i] * std::max(muSg, 0.0f) + groundSky[i]);
    }
    return l;
  }

  // The sky's irradiance on a horizontal patch of ground, per unit solar irradiance (a 32 x 64
  // midpoint quadrature over the upper hemisphere).
  void buildGroundSky() {
    groundSky.fill(0.0f);
    std::vector<Spectrum> rows(kGroundSkyRings);
    parallelFor(0, kGroundSkyRings, [&](int a) {
      Spectrum row{};
      for (int b = 0; b < kGroundSkySectors; ++b) {
        const glm::vec4 d = groundSkyDirection(a, b);
        const Spectrum l = inscattered(shape.bottomRadius, glm::vec3(d), 0.0f, false);
        for (int i = 0; i < kSkyBands; ++i) row[i] += l[i] * d.w;
      }
      rows[static_cast<std::size_t>(a)] = row;
    });
    for (const Spectrum& row : rows)
      for (int i = 0; i < kSkyBands; ++i) groundSky[i] += row[i];
  }

  // The sky-view table ([half][row][azimuth], built by the first panorama).
  std::vector<glm::vec3> skyView;
  std::once_flag skyViewBuilt;
  float horizon = 0.0f;  // the horizon's elevation, radians, <= 0

  void buildSkyView(float albedo) {
    skyView.resize(static_cast<std::size_t>(2) * kSkyViewRows * kSkyViewAzimuths);
    parallelFor(0, 2 * kSkyViewRows, [&](int row) {
      for (int i = 0; i < kSkyViewAzimuths; ++i) {
        Spectrum l =
            inscattered(observerRadius, skyViewTexelDirection(horizon, sun, row, i), albedo, true);
        for (int k = 0; k < kSkyBands; ++k) l[k] *= top[k];
        skyView[static_cast<std::size_t>(row) * kSkyViewAzimuths + i] =
            glm::max(xyzToLinearRec709(spectrumToXyz(l)), glm::vec3(0.0f));
      }
    });
  }

  glm::vec3 skyViewAt(glm::vec3 d) const {
    const glm::vec3 c = skyViewCoordinates(horizon, sun, d);
    const BilinearTap tap =
        bilinearTap(tableIndex(c.x, kSkyViewAzimuths), tableIndex(c.y, kSkyViewRows),
                    kSkyViewAzimuths, kSkyViewRows);
    return bilinear(skyView.data() + (c.z > 0.5f ? kSkyViewRows * kSkyViewAzimuths : 0), tap);
  }
};

namespace {

// What a model computes before its sun: the optical-depth table (the planet's alone) and the
// multiple-scattering table (per unit solar irradiance, over every sun height: it depends on the
// atmosphere and the ground's albedo). The last atmosphere's pair is kept for the next model of
// the same atmosphere, so a new sun position (the viewer's time of day) costs only its own
// tables.
struct SunIndependentTables {
  std::array<BandCoefficients, kSkyBands> bands{};
  float albedo = -1.0f;
  bool multipleScattering = false;
  std::shared_ptr<const std::vector<glm::vec3>> depth;
  std::shared_ptr<const std::vector<Spectrum>> multiple;

  bool sameAtmosphere(const std::array<BandCoefficients, kSkyBands>& b, float a, bool ms) const {
    return depth && albedo == a && multipleScattering == ms &&
           std::memcmp(bands.data(), b.data(), sizeof(bands)) == 0;
  }
};

std::mutex lastTablesMutex;
SunIndependentTables lastTables;

}  // namespace

SkyModel::SkyModel(const SkyParameters& p) : params_(p), tables_(std::make_unique<Tables>()) {
  checkSkyParameters(p, "sky");
  Tables& t = *tables_;
  t.bands = bandCoefficients(atmosphereCoefficients(p));
  t.top = solarIrradianceAtTop();
  t.observerRadius = t.shape.bottomRadius + std::max(p.altitude, 0.0f);
  t.sun = ibl::sunDirection(p.sunElevation, p.sunAzimuth);
  {
    const std::lock_guard lock(lastTablesMutex);
    if (lastTables.sameAtmosphere(t.bands, p.groundAlbedo, p.multipleScattering)) {
      t.depth = *lastTables.depth;
      t.multiple = *lastTables.multiple;
    }
  }
  if (t.depth.empty()) {
    t.buildDepth();
    t.buildMultiple(p.groundAlbedo, p.multipleScattering);
    const std::lock_guard lock(lastTablesMutex);
    lastTables = {t.bands, p.groundAlbedo, p.multipleScattering,
                  std::make_shared<const std::vector<glm::vec3>>(t.depth),
                  std::make_shared<const std::vector<Spectrum>>(t.multiple)};
  }
  if (p.groundAlbedo > 0.0f) t.buildGroundSky();
  t.horizon = shared::horizonElevation(t.shape, t.observerRadius);
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

void checkSkyPanoramaSize(int width, int height) {
  if (width < 2 || height < 1 || width > 16384 || height > 8192)
    fail("sky", fmt::format("panorama size {}x{} out of range", width, height));
}

Light skySun(const SkyParameters& p) {
  checkSkyParameters(p, "sky");
  const AtmosphereShape shape = earth();
  const glm::vec3 direction = sunDirection(p.sunElevation, p.sunAzimuth);
  const float r = shape.bottomRadius + p.altitude;
  Spectrum e{};
  if (!rayMeetsGround(r, direction.y, shape.bottomRadius)) {
    const glm::vec3 column = columnDensitiesToTop(shape, r, direction.y);
    const auto bands = bandCoefficients(atmosphereCoefficients(p));
    for (int i = 0; i < kSkyBands; ++i)
      e[i] = solarIrradianceAtTop()[i] * std::exp(-bandExtinction(bands[i], column));
  }
  const glm::vec3 xyz = spectrumToXyz(e);
  Light light;
  light.type = LightType::Sun;
  light.name = "sky: sun";
  light.direction = direction;
  light.angularDiameter = static_cast<float>(kSunAngularDiameter);
  light.intensity = std::max(xyz.y, 0.0f);
  const glm::vec3 rgb = xyzToLinearRec709(xyz);
  light.color = xyz.y > 0.0f ? rgb / xyz.y : glm::vec3(1.0f);
  return light;
}

Light SkyModel::sun() const {
  return skySun(params_);
}

Image SkyModel::panorama(int width, int height, bool paintSun) const {
  checkSkyPanoramaSize(width, height);
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
  if (paintSun) paintSunDisk(image, sun());
  return image;
}

void paintSunDisk(Image& image, const Light& s) {
  if (s.intensity <= 0.0f) return;
  const int width = image.width, height = image.height;
  const float w = static_cast<float>(width), h = static_cast<float>(height);
  // The disk, limb-darkened, supersampled 16 x 16 per pixel near it, then scaled so that the
  // pixels' radiance times their solid angle adds up to the sun's illuminance exactly.
  const double radius = 0.5 * static_cast<double>(s.angularDiameter);
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
  if (weighted <= 0.0) return;
  const glm::vec3 irradiance = s.color * s.intensity;  // Rec.709 "lux" per channel
  for (const auto& [index, relative] : covered)
    image.pixels[index] += irradiance * static_cast<float>(relative / weighted);
}

}  // namespace ibl
