// include/ibl/shared/iridescence.h (KHR_materials_iridescence's thin-film Fresnel) against an
// independent computation of the same optics: the film's reflectance at each wavelength from the
// Airy sum of its amplitudes (complex arithmetic, every order), integrated against the CIE 1931
// observer (Wyman, Sloan & Shirley 2013's multi-lobe fit of the matching functions, not the
// Gaussian Fourier fits the header uses), then the header's limits: no film, a thick film, a
// strength of 0. And fresnelOf and directionalReflectance (ibl/shared/material.h) on top.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

#include <gtest/gtest.h>

#include "ibl/shared/material.h"
#include "support/numbers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// Wyman, Sloan & Shirley 2013, "Simple Analytic Approximations to the CIE XYZ Color Matching
// Functions", the multi-lobe fit (their equation 2); lambda in nm.
double piecewiseGaussian(double x, double mu, double below, double above) {
  const double t = (x - mu) / (x < mu ? below : above);
  return std::exp(-0.5 * t * t);
}
glm::dvec3 colorMatching(double lambda) {
  return {1.056 * piecewiseGaussian(lambda, 599.8, 37.9, 31.0) +
              0.362 * piecewiseGaussian(lambda, 442.0, 16.0, 26.7) -
              0.065 * piecewiseGaussian(lambda, 501.1, 20.4, 26.2),
          0.821 * piecewiseGaussian(lambda, 568.8, 46.9, 40.5) +
              0.286 * piecewiseGaussian(lambda, 530.9, 16.3, 31.1),
          1.217 * piecewiseGaussian(lambda, 437.0, 11.8, 36.0) +
              0.681 * piecewiseGaussian(lambda, 459.0, 26.0, 13.8)};
}

// sRGB's (IEC 61966-2-1) XYZ to linear RGB, row by row.
glm::dvec3 rec709FromXyz(glm::dvec3 c) {
  return {3.2404542 * c.x - 1.5371385 * c.y - 0.4985314 * c.z,
          -0.9692660 * c.x + 1.8760108 * c.y + 0.0415560 * c.z,
          0.0556434 * c.x - 0.2040259 * c.y + 1.0572252 * c.z};
}

double schlick(double f0, double cosine) {
  return f0 + (1.0 - f0) * std::pow(1.0 - cosine, 5.0);
}

// The film of the extension's model, one channel of its base: air (index 1) over a film of index
// `film` and thickness d (nm) over a base of normal reflectance f0, seen at cos theta1 = c1. Its
// interfaces' reflectances are Schlick's (R12 at theta1, R23 at the refracted theta2), their
// phases 0 or pi by which side has the higher index; the film's reflectance at wavelength lambda
// is |r12 + t12 t21 r23 e^(i D) / (1 - r21 r23 e^(i D))|^2 with D = 2 pi 2 film d cos theta2 /
// lambda (every order of the Airy sum). The extension's m = 0 term, the incoherent sum R12 +
// T^2 R23 / (1 - R12 R23), is grey; what the phase adds is integrated against the observer and
// normalized by y-bar's integral, as the extension's sensitivity is.
double airyFilmReflectance(double film, double d, double c1, double f0, int channel) {
  const double s2 = (1.0 - c1 * c1) / (film * film);
  const double c2 = std::sqrt(1.0 - s2);
  const double R12 = schlick(std::pow((film - 1.0) / (film + 1.0), 2.0), c1), T = 1.0 - R12;
  const double baseIor = (1.0 + std::sqrt(f0 + 1e-4)) / (1.0 - std::sqrt(f0 + 1e-4));
  const double R23 = schlick(std::pow((baseIor - film) / (baseIor + film), 2.0), c2);
  const double phi12 = film < 1.0 ? kPi : 0.0, phi21 = kPi - phi12;
  const double phi23 = baseIor < film ? kPi : 0.0;
  const std::complex<double> r12 = std::polar(std::sqrt(R12), phi12);
  const std::complex<double> r21 = std::polar(std::sqrt(R12), phi21);
  const double incoherent = R12 + T * T * R23 / (1.0 - R12 * R23);
  glm::dvec3 xyz(0.0);
  double yIntegral = 0.0;
  for (double lambda = 360.0; lambda < 830.0; lambda += 0.25) {
    const double D = 2.0 * kPi * 2.0 * film * d * c2 / lambda;
    const std::complex<double> r23 = std::polar(std::sqrt(R23), phi23 + D);
    const double R = std::norm(r12 + T * r23 / (1.0 - r21 * r23));
    const glm::dvec3 cmf = colorMatching(lambda);
    xyz += cmf * (R - incoherent);
    yIntegral += cmf.y;
  }
  return incoherent + rec709FromXyz(xyz / yIntegral)[channel];
}

struct FilmCase {
  float film, thickness, cosine;
  glm::vec3 f0;
  double tolerance;
};

}  // namespace

// Dielectric bases (F0 0.04) under films from soap (1.3) to titanium dioxide (2.0), thin and
// thick, at normal and grazing views, and two metals' colors: the header's closed form (the Airy
// series to its second harmonic, the observer as Gaussians in Fourier space) against every order
// and the fitted observer, within 0.005 on the dielectrics (measured 0.0034) and 0.02 on the
// metals (0.013), whose brighter second interface makes the third harmonic matter. A film of the
// base's own index (1.5 over F0 0.04) reflects almost only at its top; there the extension's
// floor of 1e-5 on R12 R23 leaves a residue of 0.006 (tolerance 0.008). A film's
// color swings by 0.05 to 0.2 over these cases; the interference's phase flipped (phi21 =
// phi12) moves them by as much.
TEST(Iridescence, ThinFilmFresnelEqualsTheAiryReflectanceOverTheSpectrum) {
  const FilmCase cases[] = {
      {1.3f, 400.0f, 1.0f, glm::vec3(0.04f), 0.005}, {1.3f, 300.0f, 0.5f, glm::vec3(0.04f), 0.005},
      {1.8f, 250.0f, 0.8f, glm::vec3(0.04f), 0.005}, {2.0f, 150.0f, 0.3f, glm::vec3(0.04f), 0.005},
      {1.5f, 600.0f, 0.9f, glm::vec3(0.04f), 0.008}, {1.3f, 500.0f, 0.9f, {0.9f, 0.6f, 0.3f}, 0.02},
      {1.3f, 800.0f, 0.7f, glm::vec3(0.5f), 0.02}};
  double worstDielectric = 0.0, worstMetal = 0.0;
  for (const FilmCase& c : cases) {
    const glm::vec3 f = shared::thinFilmFresnel(1.0f, c.film, c.thickness, c.cosine, c.f0);
    for (int k = 0; k < 3; ++k) {
      const double expected = airyFilmReflectance(c.film, c.thickness, c.cosine, c.f0[k], k);
      EXPECT_NEAR(f[k], expected, c.tolerance) << "film " << c.film << ", " << c.thickness
                                               << " nm, cos " << c.cosine << ", channel " << k;
      double& worst = c.f0 == glm::vec3(0.04f) ? worstDielectric : worstMetal;
      worst = std::max(worst, std::abs(f[k] - expected));
    }
  }
  std::printf("thin film against the Airy sum over the spectrum: dielectrics %.4f, metals %.4f\n",
              worstDielectric, worstMetal);
}

// The limits: a film of no thickness vanishes (at normal incidence the base's F0 remains, the
// series' residue under 0.01); one far thicker than the light's coherence leaves the incoherent
// sum R12 + T^2 R23 / (1 - R12 R23) alone (the harmonics' Gaussian envelopes vanish); total
// internal reflection inside the film (a film of index < 1 at a grazing view) reflects all.
TEST(Iridescence, LimitsOfTheFilm) {
  const glm::vec3 f0(0.04f, 0.3f, 0.8f);
  const glm::vec3 none = shared::thinFilmFresnel(1.0f, 1.6f, 0.0f, 1.0f, f0);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(none[k], f0[k], 0.01) << k;
  const float c1 = 0.6f, film = 1.4f;
  const glm::vec3 thick = shared::thinFilmFresnel(1.0f, film, 20000.0f, c1, f0);
  const double c2 = std::sqrt(1.0 - (1.0 - c1 * c1) / (film * film));
  const double R12 = schlick(std::pow((film - 1.0) / (film + 1.0), 2.0), c1), T = 1.0 - R12;
  for (int k = 0; k < 3; ++k) {
    const double n = (1.0 + std::sqrt(f0[k] + 1e-4)) / (1.0 - std::sqrt(f0[k] + 1e-4));
    const double R23 = schlick(std::pow((n - film) / (n + film), 2.0), c2);
    EXPECT_NEAR(thick[k], R12 + T * T * R23 / (1.0 - R12 * R23), 1e-4) << k;
  }
  EXPECT_EQ(shared::thinFilmFresnel(1.0f, 0.8f, 300.0f, 0.2f, f0), glm::vec3(1.0f));
}

// fresnelOf: Schlick's term with no film; with one, the mix toward the film's by the strength.
// directionalReflectance: the DFG's F0 A + F90 B with no film, the film's Fresnel at n.v times
// A + B with a full one (a mirror's A + B = 1 makes it the film's Fresnel there exactly).
TEST(Iridescence, StrengthMixesTheFilmIntoTheFresnelTerm) {
  shared::SpecularReflectance r = shared::schlickReflectance(glm::vec3(0.04f, 0.05f, 0.06f), 0.8f);
  const float cosine = 0.35f;
  const glm::vec3 schlickTerm = r.f0 + (glm::vec3(r.f90) - r.f0) * std::pow(1.0f - cosine, 5.0f);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(shared::fresnelOf(r, cosine)[k], schlickTerm[k], 1e-6f);
  const glm::vec3 film = shared::thinFilmFresnel(1.0f, 1.5f, 350.0f, cosine, r.f0);
  r = shared::withIridescence(r, 0.25f, 1.5f, 350.0f);
  const glm::vec3 mixed = shared::fresnelOf(r, cosine);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(mixed[k], 0.75f * schlickTerm[k] + 0.25f * film[k], 1e-6f);
  const glm::vec2 dfg(0.6f, 0.3f);
  r.iridescence = 1.0f;
  const glm::vec3 albedo = shared::directionalReflectance(r, dfg, cosine);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(albedo[k], film[k] * 0.9f, 1e-6f);
  r.iridescence = 0.0f;
  const glm::vec3 plain = shared::directionalReflectance(r, dfg, cosine);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(plain[k], r.f0[k] * 0.6f + 0.8f * 0.3f, 1e-6f);
}
