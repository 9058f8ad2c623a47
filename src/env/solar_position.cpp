// The Sun's position in the sky (Meeus 1998, "Astronomical Algorithms", 2nd edition).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "ibl/env/sky.hpp"

namespace ibl {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

double normalizedDegrees(double a) {
  a = std::fmod(a, 360.0);
  return a < 0.0 ? a + 360.0 : a;
}

// Atmospheric refraction of a body at true elevation h degrees, in degrees (Saemundsson 1986,
// Meeus eq. 16.4, scaled for pressure and temperature as Meeus suggests), 0 well below the
// horizon.
double refraction(double h, double pressureHpa, double celsius) {
  if (h < -1.0) return 0.0;
  const double arcmin = 1.02 / std::tan((h + 10.3 / (h + 5.11)) * kDegree);
  return arcmin / 60.0 * (pressureHpa / 1010.0) * (283.0 / (273.0 + celsius));
}

}  // namespace

double julianDay(int year, int month, int day, double utcHours) {
  // Meeus eq. 7.1 (Gregorian calendar).
  if (month <= 2) {
    year -= 1;
    month += 12;
  }
  const int a = year / 100;
  const int b = 2 - a + a / 4;
  return std::floor(365.25 * (year + 4716)) + std::floor(30.6001 * (month + 1)) + day + b - 1524.5 +
         utcHours / 24.0;
}

SolarPosition solarCoordinates(double jd) {
  const double t = (jd - 2451545.0) / 36525.0;  // Julian centuries from J2000.0 (eq. 25.1)
  // Geometric mean longitude, mean anomaly (eq. 25.2, 25.3).
  const double l0 = 280.46646 + t * (36000.76983 + t * 0.0003032);
  const double m = (357.52911 + t * (35999.05029 - t * 0.0001537)) * kDegree;
  // Equation of the center, true and apparent longitude (chapter 25).
  const double c = (1.914602 - t * (0.004817 + t * 0.000014)) * std::sin(m) +
                   (0.019993 - t * 0.000101) * std::sin(2.0 * m) + 0.000289 * std::sin(3.0 * m);
  const double omega = (125.04 - 1934.136 * t) * kDegree;
  const double lambda = (l0 + c - 0.00569 - 0.00478 * std::sin(omega)) * kDegree;
  // Mean obliquity of the ecliptic (eq. 22.2), corrected for the apparent position (eq. 25.8).
  const double e0 =
      23.0 + (26.0 + (21.448 - t * (46.8150 + t * (0.00059 - t * 0.001813))) / 60.0) / 60.0;
  const double epsilon = (e0 + 0.00256 * std::cos(omega)) * kDegree;
  SolarPosition p;
  p.rightAscension = normalizedDegrees(
      std::atan2(std::cos(epsilon) * std::sin(lambda), std::cos(lambda)) / kDegree);
  p.declination = std::asin(std::sin(epsilon) * std::sin(lambda)) / kDegree;
  return p;
}

SolarPosition solarPosition(const DateTime& when, double latitude, double longitude,
                            double altitudeMeters) {
  const double jd = julianDay(when.year, when.month, when.day, when.hours - when.utcOffset);
  SolarPosition p = solarCoordinates(jd);
  // Greenwich mean sidereal time (eq. 12.4), the local hour angle (longitude east-positive).
  const double t = (jd - 2451545.0) / 36525.0;
  const double theta0 =
      280.46061837 + 360.98564736629 * (jd - 2451545.0) + t * t * (0.000387933 - t / 38710000.0);
  const double hourAngle = (theta0 + longitude - p.rightAscension) * kDegree;
  const double phi = latitude * kDegree, delta = p.declination * kDegree;
  // Horizontal coordinates (eq. 13.5, 13.6), the azimuth turned to count from north.
  const double sinH =
      std::sin(phi) * std::sin(delta) + std::cos(phi) * std::cos(delta) * std::cos(hourAngle);
  const double h = std::asin(std::clamp(sinH, -1.0, 1.0)) / kDegree;
  const double azimuthFromSouth = std::atan2(
      std::sin(hourAngle), std::cos(hourAngle) * std::sin(phi) - std::tan(delta) * std::cos(phi));
  p.azimuth = normalizedDegrees(azimuthFromSouth / kDegree + 180.0);
  // The standard atmosphere's pressure at the observer's altitude, at 15 degrees Celsius.
  const double pressure = 1013.25 * std::exp(-altitudeMeters / 8434.0);
  p.elevation = h + refraction(h, pressure, 15.0);
  return p;
}

}  // namespace ibl
