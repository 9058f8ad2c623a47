// API: internal (may change without notice; math shared with the shaders)
// A clear-sky atmosphere over a spherical planet: the geometry of rays in (r, mu) coordinates
// (r: distance from the planet's center, mu: cosine of the ray's zenith angle), the density
// profiles of its three constituents, and their phase functions. C++ and GLSL (see lang.h):
// src/env/sky.cpp integrates them over wavelengths. Sources: Bruneton & Neyret 2008, "Precomputed
// Atmospheric Scattering" (section 4 for the geometry); Bruneton 2017, "A Qualitative and
// Quantitative Evaluation of 8 Clear Sky Models" (the ozone layer); Hillaire 2020, "A Scalable and
// Production Ready Sky and Atmosphere Rendering Technique" (the multiple-scattering
// approximation, section 5.5).
#ifndef IBL_SHARED_SKY_H
#define IBL_SHARED_SKY_H
#include "ibl/shared/lang.h"

IBL_BEGIN

// The planet and the constituents' profiles, in meters.
struct AtmosphereShape {
  float bottomRadius;    // the ground
  float topRadius;       // where the density is taken as zero
  float rayleighHeight;  // scale height of the air molecules
  float mieHeight;       // scale height of the aerosols
  float ozoneCenter;     // altitude of the ozone layer's peak (tent profile)
  float ozoneHalfWidth;  // half of the tent's base
};

// The three densities at altitude h, relative to their reference: air and aerosols at sea level
// (exp(-h / H)), ozone at its peak (a tent, 1 at ozoneCenter, 0 beyond ozoneHalfWidth from it).
IBL_FN vec3 constituentDensities(AtmosphereShape a, float h) {
  vec3 d;
  d.x = exp(-h / a.rayleighHeight);
  d.y = exp(-h / a.mieHeight);
  d.z = max(0.0f, 1.0f - abs(h - a.ozoneCenter) / a.ozoneHalfWidth);
  return d;
}

// The distance from radius r along a ray of zenith cosine mu to the sphere of radius `radius`
// (the far root: the top of the atmosphere from inside it; Bruneton & Neyret eq. 2 solved).
IBL_FN float distanceToSphereFar(float r, float mu, float radius) {
  float disc = r * r * (mu * mu - 1.0f) + radius * radius;
  return max(0.0f, -r * mu + sqrt(max(disc, 0.0f)));
}

// The distance to the ground along the ray, the near root; only meaningful when the ray meets
// it (rayMeetsGround).
IBL_FN float distanceToGround(float r, float mu, float groundRadius) {
  float disc = r * r * (mu * mu - 1.0f) + groundRadius * groundRadius;
  return max(0.0f, -r * mu - sqrt(max(disc, 0.0f)));
}

// Whether a ray from radius r (at or above the ground) of zenith cosine mu meets the planet.
IBL_FN bool rayMeetsGround(float r, float mu, float groundRadius) {
  return mu < 0.0f && r * r * (mu * mu - 1.0f) + groundRadius * groundRadius >= 0.0f;
}

// Where a ray from radius r with zenith cosine mu is after a distance t: its new radius and
// zenith cosine (the law of cosines; Bruneton & Neyret 2008, eq. 5).
IBL_FN vec2 radiusAndCosineAfter(float r, float mu, float t) {
  float rt = sqrt(max(t * t + 2.0f * r * mu * t + r * r, 1.0f));
  vec2 result;
  result.x = rt;
  result.y = clamp((r * mu + t) / rt, -1.0f, 1.0f);
  return result;
}

// Rayleigh's phase function, 3 (1 + cos^2) / (16 pi): integrates to 1 over the sphere.
IBL_FN float rayleighPhase(float cosTheta) {
  return 3.0f / (16.0f * 3.14159265358979f) * (1.0f + cosTheta * cosTheta);
}

// The Cornette-Shanks phase function for aerosols (Cornette & Shanks 1992, eq. 4; the
// Henyey-Greenstein lobe made to integrate to 1 with a Rayleigh-like 1 + cos^2 factor).
IBL_FN float cornetteShanksPhase(float cosTheta, float g) {
  float g2 = g * g;
  float k = 3.0f / (8.0f * 3.14159265358979f) * (1.0f - g2) / (2.0f + g2);
  return k * (1.0f + cosTheta * cosTheta) / pow(1.0f + g2 - 2.0f * g * cosTheta, 1.5f);
}

// ---- Spectral constants and the march, per band ----------------------------------------------

// The number of wavelength bands the sky is computed in (src/env/sky.cpp: 20 nm wide, 380 to 780).
const int kSkyBands = 20;

// One band's optical constants at the constituents' reference densities, m^-1.
struct BandCoefficients {
  float rayleigh;       // scattering = extinction of the molecules
  float mieScattering;  // aerosols
  float mieExtinction;
  float ozone;  // absorption only
};

// The band's extinction coefficient for the densities `rho` (or, given column densities, its
// optical depth).
IBL_FN float bandExtinction(BandCoefficients c, vec3 rho) {
  return c.rayleigh * rho.x + c.mieExtinction * rho.y + c.ozone * rho.z;
}

// The band's in-scattering source per unit solar irradiance at a point of densities `rho`: the
// sun's light seen through `sunTransmittance` scattered toward the viewer by the two phase
// functions, plus the multiple-scattering light `psi` (Hillaire 2020, eq. 10, psi isotropic).
IBL_FN float bandInscatteringSource(BandCoefficients c, vec3 rho, float phaseR, float phaseM,
                                    float sunTransmittance, float psi) {
  float rayleigh = c.rayleigh * rho.x;
  float mie = c.mieScattering * rho.y;
  return rayleigh * (phaseR * sunTransmittance + psi) + mie * (phaseM * sunTransmittance + psi);
}

// The band's scattering coefficient for the densities `rho`.
IBL_FN float bandScattering(BandCoefficients c, vec3 rho) {
  return c.rayleigh * rho.x + c.mieScattering * rho.y;
}

// The integral over a step of length dt of the attenuation exp(-extinction t), given the step's
// transmittance exp(-extinction dt): a constant source integrated with the step's own extinction
// (Hillaire 2020, section 5.6.3: energy-conserving integration).
IBL_FN float stepIntegral(float extinction, float dt, float stepTransmittance) {
  return extinction > 0.0f ? (1.0f - stepTransmittance) / extinction : dt;
}

// Step s of n along a ray of `length`, spaced quadratically (short where the march starts, near
// the observer, where the density and the view change fastest): the step's middle and length.
IBL_FN vec2 quadraticStep(float length, int s, int n) {
  float s0 = float(s) / float(n);
  float s1 = float(s + 1) / float(n);
  vec2 step;
  step.x = length * 0.5f * (s0 * s0 + s1 * s1);
  step.y = length * (s1 * s1 - s0 * s0);
  return step;
}

// The sun's zenith cosine at distance t along a ray that leaves radius r0, where the radius has
// become rt: mu_s' = (r0 mu_s + t nu) / rt (Bruneton & Neyret 2008, section 4).
IBL_FN float sunCosineAfter(float r0, float muS, float nu, float t, float rt) {
  return clamp((r0 * muS + t * nu) / rt, -1.0f, 1.0f);
}

// The column densities (relative to the reference densities, in meters) from radius r along
// zenith cosine mu to the top of the atmosphere: 256 quadratically spaced midpoint steps. The
// ray must miss the ground.
IBL_FN vec3 columnDensitiesToTop(AtmosphereShape a, float r, float mu) {
  float length = distanceToSphereFar(r, mu, a.topRadius);
  vec3 sum = vec3(0.0f);
  for (int i = 0; i < 256; ++i) {
    vec2 step = quadraticStep(length, i, 256);
    float h = radiusAndCosineAfter(r, mu, step.x).x - a.bottomRadius;
    sum += constituentDensities(a, h) * step.y;
  }
  return sum;
}

// ---- The tables' parameterizations (texel-centered coordinates in [0, 1]) -------------------

const int kDepthTableMu = 256;
const int kDepthTableR = 64;
const int kMultipleTableMu = 32;
const int kMultipleTableR = 32;
const int kSkyViewAzimuths = 256;
const int kSkyViewRows = 160;  // per half: above and below the horizon

// A coordinate in [0, 1] as a continuous texel index in [0, n - 1].
IBL_FN float tableIndex(float x, int n) {
  return clamp(x, 0.0f, 1.0f) * float(n - 1);
}

// The distance from the ground to the top of the atmosphere along the horizon.
IBL_FN float horizonDistance(AtmosphereShape a) {
  return sqrt(a.topRadius * a.topRadius - a.bottomRadius * a.bottomRadius);
}

// The optical-depth table's coordinates of (r, mu), for rays that miss the ground (Bruneton
// 2017, GetTransmittanceTextureUvFromRMu): x the distance to the top between its extremes, y the
// distance to the horizon.
IBL_FN vec2 depthTableCoordinates(AtmosphereShape a, float r, float mu) {
  float H = horizonDistance(a);
  float rho = sqrt(max(r * r - a.bottomRadius * a.bottomRadius, 0.0f));
  float d = distanceToSphereFar(r, mu, a.topRadius);
  float dMin = a.topRadius - r;
  float dMax = rho + H;
  vec2 xy;
  xy.x = dMax > dMin ? (d - dMin) / (dMax - dMin) : 0.0f;
  xy.y = rho / H;
  return xy;
}

// Its inverse (Bruneton 2017, GetRMuFromTransmittanceTextureUv): (r, mu) of coordinates (x, y).
IBL_FN vec2 depthTableRadiusAndCosine(AtmosphereShape a, float x, float y) {
  float H = horizonDistance(a);
  float rho = H * y;
  float r = sqrt(rho * rho + a.bottomRadius * a.bottomRadius);
  float dMin = a.topRadius - r;
  float dMax = rho + H;
  float d = dMin + x * (dMax - dMin);
  vec2 rm;
  rm.x = r;
  rm.y = d == 0.0f ? 1.0f : clamp((H * H - rho * rho - d * d) / (2.0f * r * d), -1.0f, 1.0f);
  return rm;
}

// The multiple-scattering table's coordinates of (r, mu_s): linear in both (Hillaire 2020, 5.5).
IBL_FN vec2 multipleTableCoordinates(AtmosphereShape a, float r, float muS) {
  vec2 xy;
  xy.x = 0.5f + 0.5f * muS;
  xy.y = (r - a.bottomRadius) / (a.topRadius - a.bottomRadius);
  return xy;
}

// Its inverse, with the ground row lifted a hair above the ground.
IBL_FN vec2 multipleTableRadiusAndCosine(AtmosphereShape a, float x, float y) {
  vec2 rm;
  rm.x = a.bottomRadius + (a.topRadius - a.bottomRadius) * max(y, 1e-4f);
  rm.y = -1.0f + 2.0f * x;
  return rm;
}

// Direction (a, b) of the n x n stratified directions over the sphere that Hillaire's
// multiple-scattering integral averages over (equal solid angles: uniform in cos theta and phi),
// in a frame whose +Y is the zenith.
IBL_FN vec3 sphereStratumDirection(int a, int b, int n) {
  float cosTheta = 1.0f - 2.0f * (float(a) + 0.5f) / float(n);
  float phi = 2.0f * kPi * (float(b) + 0.5f) / float(n);
  float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
  return vec3(sinTheta * cos(phi), cosTheta, sinTheta * sin(phi));
}

// The sky's irradiance on the ground is a midpoint quadrature over the upper hemisphere in
// rings of equal zenith angle and sectors of equal azimuth: direction (a, b) and its weight, the
// integral of cos(theta) over its cell.
const int kGroundSkyRings = 32;
const int kGroundSkySectors = 64;
IBL_FN vec4 groundSkyDirection(int a, int b) {
  float t0 = 0.5f * kPi * float(a) / float(kGroundSkyRings);
  float t1 = 0.5f * kPi * float(a + 1) / float(kGroundSkyRings);
  float theta = 0.5f * (t0 + t1);
  float phi = 2.0f * kPi * (float(b) + 0.5f) / float(kGroundSkySectors);
  float weight = 0.25f * (cos(2.0f * t0) - cos(2.0f * t1)) * 2.0f * kPi / float(kGroundSkySectors);
  return vec4(sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi), weight);
}

// The elevation (radians, <= 0) of the geometric horizon seen from radius r.
IBL_FN float horizonElevation(AtmosphereShape a, float r) {
  return -acos(min(a.bottomRadius / r, 1.0f));
}

// The sky-view table (after Hillaire 2020, section 5.3): the view's azimuth from the sun's (0 to
// pi: the sky is symmetric about the sun's vertical plane) and its elevation, in two halves that
// meet at the horizon (the ground's edge is a discontinuity no interpolation may cross), each
// with rows crowded toward the horizon (the elevation from it grows as the square of the row
// coordinate). The angular span of a half:
IBL_FN float skyViewSpan(float horizon, bool below) {
  return below ? horizon + 0.5f * kPi : 0.5f * kPi - horizon;
}

// The elevation (radians) of row coordinate t in [0, 1] of a half.
IBL_FN float skyViewElevation(float horizon, bool below, float t) {
  return horizon + (below ? -1.0f : 1.0f) * skyViewSpan(horizon, below) * t * t;
}

// The compass azimuth (radians, from north -Z toward east +X) of a direction.
IBL_FN float compassAzimuth(vec3 d) {
  return atan(d.x, -d.z);
}

// The direction at elevation e and azimuth `a` from the sun's.
IBL_FN vec3 skyViewDirection(vec3 sun, float e, float a) {
  float compass = compassAzimuth(sun) + a;
  return vec3(cos(e) * sin(compass), sin(e), -cos(e) * cos(compass));
}

// The direction of texel (row, i) of the table, rows [0, kSkyViewRows) above the horizon and
// the next kSkyViewRows below it; the rows at the horizon sit just on their side of it.
IBL_FN vec3 skyViewTexelDirection(float horizon, vec3 sun, int row, int i) {
  bool below = row >= kSkyViewRows;
  int j = below ? row - kSkyViewRows : row;
  float e = skyViewElevation(horizon, below, float(j) / float(kSkyViewRows - 1));
  if (j == 0) e += below ? -1e-5f : 1e-5f;
  return skyViewDirection(sun, e, kPi * float(i) / float(kSkyViewAzimuths - 1));
}

// The table coordinates of direction d: x the azimuth from the sun's over pi, y the row
// coordinate within its half, z 1 below the horizon and 0 above.
IBL_FN vec3 skyViewCoordinates(float horizon, vec3 sun, vec3 d) {
  float e = asin(clamp(d.y, -1.0f, 1.0f));
  bool below = e < horizon;
  float span = skyViewSpan(horizon, below);
  float a = abs(compassAzimuth(d) - compassAzimuth(sun));
  if (a > kPi) a = 2.0f * kPi - a;
  vec3 xyz;
  xyz.x = a / kPi;
  xyz.y = span > 0.0f ? sqrt(abs(e - horizon) / span) : 0.0f;
  xyz.z = below ? 1.0f : 0.0f;
  return xyz;
}

IBL_END

#endif
