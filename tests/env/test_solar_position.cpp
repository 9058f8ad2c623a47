// The solar position against published examples: Meeus's low-accuracy method and NREL's solar
// position algorithm (Reda & Andreas), and the geometry of noon at a solstice.
#include <cstdio>

#include <gtest/gtest.h>

#include "ibl/env/sky.hpp"

using namespace ibl;

TEST(SolarPosition, MeeusExample25a) {
  // Meeus 1998, example 25.a: 1992 October 13.0 TD; apparent right ascension 198.38083 degrees,
  // declination -7.78507 degrees (low-accuracy method).
  const double jd = julianDay(1992, 10, 13, 0.0);
  EXPECT_DOUBLE_EQ(jd, 2448908.5);
  const SolarPosition p = solarCoordinates(jd);
  EXPECT_NEAR(p.rightAscension, 198.38083, 2e-4);
  EXPECT_NEAR(p.declination, -7.78507, 2e-4);
}

TEST(SolarPosition, ReadaAndAndreasExample) {
  // Reda & Andreas 2004, "Solar position algorithm for solar radiation applications" (NREL),
  // table A5.1: Golden, Colorado (39.742476 N, 105.1786 W, 1830 m), 2003-10-17 12:30:30 local
  // time (UTC-7): topocentric zenith angle 50.11162 degrees, azimuth 194.34024 degrees.
  DateTime when;
  when.year = 2003;
  when.month = 10;
  when.day = 17;
  when.hours = 12.5 + 30.0 / 3600.0;
  when.utcOffset = -7.0;
  const SolarPosition p = solarPosition(when, 39.742476, -105.1786, 1830.14);
  std::printf("elevation %.5f (SPA %.5f), azimuth %.5f (SPA 194.34024)\n", p.elevation,
              90.0 - 50.11162, p.azimuth);
  // Measured 1e-4 and 2e-4 degrees; refraction alone is 0.016 degrees here.
  EXPECT_NEAR(p.elevation, 90.0 - 50.11162, 0.003);
  EXPECT_NEAR(p.azimuth, 194.34024, 0.003);
}

TEST(SolarPosition, NoonAndSolsticeGeometry) {
  // At the June solstice of 2024 (20 June, 20:51 UTC) the declination is +23.44 degrees; at the
  // local noon of the longitude where that is noon the sun stands 90 - |latitude - 23.44| high,
  // due south north of the tropic.
  const SolarPosition s = solarCoordinates(julianDay(2024, 6, 20, 20.0 + 51.0 / 60.0));
  EXPECT_NEAR(s.declination, 23.44, 0.01);
  DateTime when;
  when.year = 2024;
  when.month = 6;
  when.day = 20;
  when.hours = 20.0 + 51.0 / 60.0;
  // 20:51 UTC is apparent noon at about 132.9 W (the equation of time is -1.7 minutes).
  const SolarPosition p = solarPosition(when, 50.0, -132.33, 0.0);
  EXPECT_NEAR(p.elevation, 90.0 - (50.0 - 23.44), 0.05);
  EXPECT_NEAR(p.azimuth, 180.0, 0.5);
}
