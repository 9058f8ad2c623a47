#pragma once
// API: stable
// A physically based clear sky: Rayleigh and Mie scattering and ozone absorption over a
// spherical planet, single and multiple scattering, integrated over the visible spectrum and
// written as linear Rec.709 radiance in cd/m^2, with the sun as a light in lux. docs/sky.md has
// the model, its sources and its measured figures.
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <glm/ext/vector_double3.hpp>
#include <glm/vec3.hpp>

#include "ibl/core/image.hpp"
#include "ibl/render/light.hpp"
#include "ibl/shared/sky.h"

namespace ibl {

// The wavelengths the sky is computed at: the centers of 20 bands 20 nm wide from 380 to 780 nm
// (390, 410, ... 770 nm; the color matching functions are integrated by the midpoint rule).
inline constexpr int kSkyBands = shared::kSkyBands;
inline constexpr float kSkyFirstWavelength = 390.0f, kSkyBandWidth = 20.0f;
using Spectrum = std::array<float, kSkyBands>;

// Wavelength of band i, nm.
constexpr float skyWavelength(int band) {
  return kSkyFirstWavelength + kSkyBandWidth * static_cast<float>(band);
}

// The sun's direction from its elevation above the horizon and its compass azimuth (from north
// toward east), degrees: north is -Z, east +X, up +Y.
glm::vec3 sunDirection(float elevationDegrees, float azimuthDegrees);

struct SkyParameters {
  float sunElevation = 30.0f;  // degrees above the horizon (-90 to 90)
  float sunAzimuth = 180.0f;   // degrees, compass (0 north, 90 east)
  float altitude = 0.0f;       // of the observer above the ground, meters (0 to 80 km)
  float turbidity = 2.0f;     // 1 + aerosol optical depth / Rayleigh optical depth at 550 nm (1-20)
  float ozone = 300.0f;       // ozone column, Dobson units (0: none, up to 1000)
  float groundAlbedo = 0.3f;  // Lambertian, 0 to 1
  bool multipleScattering = true;  // false: single scattering only
};

// Throws UsageError("<what>: ...") for a parameter out of its range (elevation -90 to 90,
// azimuth -360 to 360, the ranges above otherwise).
void checkSkyParameters(const SkyParameters& p, std::string_view what);

// The atmosphere's spectral coefficients at sea level (the ozone's at its peak), m^-1, per band.
struct AtmosphereCoefficients {
  Spectrum rayleighScattering{};
  Spectrum mieScattering{}, mieExtinction{};
  Spectrum ozoneAbsorption{};
};
// Of p's turbidity and ozone column (the other parameters are not used).
AtmosphereCoefficients atmosphereCoefficients(const SkyParameters& p);

// The planet and the constituents' profiles (Earth: 6371 km, 100 km of atmosphere), and the
// aerosols' asymmetry parameter (0.8).
shared::AtmosphereShape skyAtmosphereShape();
float skyMieAsymmetry();

// The solar spectral irradiance at the top of the atmosphere, W m^-2 nm^-1 per band: a
// blackbody at the Sun's effective temperature seen at 1 au (about 1361 W m^-2 in all).
const Spectrum& solarIrradianceAtTop();

// The photometric XYZ weights of band i: spectrumToXyz(s) is the sum over the bands of s[i] times
// these (the color matching functions at the band's wavelength times 683 lm/W times its width).
glm::dvec3 skyBandXyz(int band);

// The photometric XYZ of a spectral radiance (W m^-2 sr^-1 nm^-1 per band) or irradiance: 683
// lm/W times the integral against the CIE 1931 color matching functions (cd/m^2 or lux in Y).
glm::vec3 spectrumToXyz(const Spectrum& s);

class SkyModel {
 public:
  // Precomputes the optical-depth and multiple-scattering tables (a few milliseconds). Throws
  // UsageError("sky: ...") for parameters out of range (checkSkyParameters).
  explicit SkyModel(const SkyParameters& p);
  ~SkyModel();
  SkyModel(SkyModel&&) noexcept;
  SkyModel& operator=(SkyModel&&) noexcept;

  // The parameters it was built with; the unit direction toward the sun (ibl::sunDirection).
  const SkyParameters& parameters() const;
  glm::vec3 sunDirection() const;

  // The transmittance of the atmosphere from the observer (at its altitude) toward unit
  // direction `d` up to the top of the atmosphere (0 through the ground), per band: a fraction,
  // 0 to 1.
  Spectrum transmittance(glm::vec3 d) const;

  // The sky's spectral radiance toward the observer from direction `d` (the sun's disk left
  // out), W m^-2 sr^-1 nm^-1 per band: in-scattered light along the ray, and where the ray meets
  // the ground, the ground's Lambertian reflection of the sun and sky.
  Spectrum radiance(glm::vec3 d) const;

  // The sun as a light: direction toward it, illuminance in lux on a surface facing it after
  // the atmosphere's transmittance, color (linear Rec.709, luminance 1), angular diameter 0.53
  // degrees. Below the horizon its illuminance is 0.
  Light sun() const;

  // The sky's panorama (equirect, docs/conventions.md): linear Rec.709 in cd/m^2. With
  // `paintSun`, the sun's disk (limb-darkened) is drawn into it carrying the sun's illuminance.
  // width, height: pixels (checkSkyPanoramaSize; throws Error("sky: ...") outside it).
  Image panorama(int width, int height, bool paintSun) const;

 private:
  struct Tables;
  SkyParameters params_;
  std::unique_ptr<Tables> tables_;
};

// Throws Error("sky: ...") unless a panorama of width x height (pixels) is in 2x1 to 16384x8192.
void checkSkyPanoramaSize(int width, int height);

// The sun of the sky `p` as a light (SkyModel::sun, without building the model's tables): the
// solar spectrum at the top of the atmosphere seen through the atmosphere's column toward it.
// Throws UsageError("sky: ...") as checkSkyParameters.
Light skySun(const SkyParameters& p);

// Draws the sun's disk, limb-darkened, into an equirect panorama so that the added radiance
// times the pixels' solid angles sums to the light's illuminance (its color times its lux).
// Nothing for a light of 0 lux. panorama: equirect in cd/m^2; sun: a directional light (lux).
void paintSunDisk(Image& panorama, const Light& sun);

// A Monte Carlo reference for SkyModel::radiance (src/env/sky_reference.cpp): a spectral
// volumetric path tracer of the same atmosphere, every order of scattering and the ground's
// reflections traced (no tables, no multiple-scattering approximation), `paths` paths per band.
// For measuring the model (tests, docs/sky.md): seconds per direction. `orders` bounds the
// scattering events (and ground reflections) of a path: 1 is single scattering. Returns
// W m^-2 sr^-1 nm^-1 per band, as SkyModel::radiance; direction: unit, as SkyModel::radiance's d.
Spectrum pathTracedSkyRadiance(const SkyParameters& p, glm::vec3 direction, int paths,
                               unsigned seed = 1, int orders = 200);

// The solar position for a date and time at a place (Meeus 1998, "Astronomical Algorithms",
// chapters 7, 12, 13 and 25, low-accuracy solar coordinates: about 0.01 degree from 1950 to
// 2050), with standard atmospheric refraction (Saemundsson 1986) for the observer's altitude.
struct SolarPosition {
  double elevation = 0.0;                          // degrees above the horizon, refraction included
  double azimuth = 0.0;                            // degrees from north toward east
  double declination = 0.0, rightAscension = 0.0;  // degrees, apparent, of date
};
struct DateTime {
  int year = 2000, month = 1, day = 1;
  double hours = 12.0;     // local clock time, hours
  double utcOffset = 0.0;  // hours east of Greenwich (UTC+2: 2)
};
// The Julian day (Meeus eq. 7.1) of a UTC instant: Gregorian date, utcHours the hours
// after its 0:00 UTC (below 0 or past 24 moves to the day before or after).
double julianDay(int year, int month, int day, double utcHours);
// latitude: degrees, north positive (-90 to 90); longitude: degrees, east positive (-180 to
// 180); altitudeMeters: the observer's, for the refraction.
SolarPosition solarPosition(const DateTime& when, double latitude, double longitude,
                            double altitudeMeters = 0.0);
// The Sun's apparent right ascension and declination at Julian day `jd` (Meeus chapter 25).
SolarPosition solarCoordinates(double jd);

// "sky:elevation=30,azimuth=120,turbidity=3,..." as ibl bake / render / view accept it. Keys:
// elevation, azimuth, or date (YYYY-MM-DD), time (HH:MM[:SS]), utc, latitude, longitude; and
// altitude, turbidity, ozone, albedo, size (WxH, default 1024x512). Throws Error naming `text`.
struct SkySpec {
  SkyParameters parameters;
  int width = 1024, height = 512;
};
// isSkySpec: whether text is "sky" or starts with "sky:". parseSkySpec throws UsageError.
bool isSkySpec(std::string_view text);
SkySpec parseSkySpec(std::string_view text);

// Parses "YYYY-MM-DD" (1900 to 2100) and "HH:MM[:SS]" into `when` (the offset left alone);
// throws UsageError naming `option`.
void parseDate(std::string_view text, DateTime& when, std::string_view option);
void parseClockTime(std::string_view text, DateTime& when, std::string_view option);

}  // namespace ibl
