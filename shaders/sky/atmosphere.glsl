// The sky's shaders (shaders/sky/*.comp) share this: the atmosphere's constants and its tables
// as buffers, and the march through them: the GPU's twin of SkyModel::Tables
// (src/env/sky.cpp), with the per-point math of ibl/shared/sky.h.
#include "ibl/shared/sky.h"

// Binding 0: the atmosphere (src/gpu/sky.cpp writes it: SkyConstants).
layout(std430, binding = 0) readonly buffer Sky {
  vec4 sunAndRadius;  // the direction toward the sun; the observer's distance from the center
  vec4 shape0;        // AtmosphereShape: bottomRadius, topRadius, rayleighHeight, mieHeight
  vec4 shape1;        // ozoneCenter, ozoneHalfWidth; the ground's albedo; Mie's asymmetry g
  vec4 flags;         // the horizon's elevation; 1 with multiple scattering
  vec4 bands[kSkyBands];  // BandCoefficients: rayleigh, mieScattering, mieExtinction, ozone
  vec4 light[kSkyBands];  // the solar irradiance at the top; the sky's on the ground per unit
  vec4 xyz[kSkyBands];    // the color matching functions times 683 lm/W times the band's width
} sky;
// Binding 1: column densities to the top, [r][mu] (kDepthTableR x kDepthTableMu).
layout(std430, binding = 1) buffer Depth { vec4 depth[]; };
// Binding 2: Psi_ms per unit solar irradiance, [r][mu_s][band].
layout(std430, binding = 2) buffer Multiple { float multiple[]; };

AtmosphereShape atmosphereShape() {
  AtmosphereShape a;
  a.bottomRadius = sky.shape0.x;
  a.topRadius = sky.shape0.y;
  a.rayleighHeight = sky.shape0.z;
  a.mieHeight = sky.shape0.w;
  a.ozoneCenter = sky.shape1.x;
  a.ozoneHalfWidth = sky.shape1.y;
  return a;
}

BandCoefficients bandCoefficients(int i) {
  BandCoefficients c;
  c.rayleigh = sky.bands[i].x;
  c.mieScattering = sky.bands[i].y;
  c.mieExtinction = sky.bands[i].z;
  c.ozone = sky.bands[i].w;
  return c;
}

// Bilinear taps at continuous texel indices (x, y) of a width x height table: the row-major
// index of the lower corner and the fractions.
void bilinearTap(float x, float y, int width, int height, out int corner, out vec2 f) {
  int x0 = min(int(x), width - 2);
  int y0 = min(int(y), height - 2);
  corner = y0 * width + x0;
  f = vec2(x - float(x0), y - float(y0));
}

// The transmittance to the top from (r, mu), per band; 0 through the ground.
void transmittanceToTop(AtmosphereShape a, float r, float mu, out float t[kSkyBands]) {
  if (rayMeetsGround(r, mu, a.bottomRadius)) {
    for (int i = 0; i < kSkyBands; ++i) t[i] = 0.0f;
    return;
  }
  vec2 xy = depthTableCoordinates(a, r, mu);
  int c;
  vec2 f;
  bilinearTap(tableIndex(xy.x, kDepthTableMu), tableIndex(xy.y, kDepthTableR), kDepthTableMu,
              kDepthTableR, c, f);
  vec3 column = mix(mix(depth[c].xyz, depth[c + 1].xyz, f.x),
                    mix(depth[c + kDepthTableMu].xyz, depth[c + kDepthTableMu + 1].xyz, f.x), f.y);
  for (int i = 0; i < kSkyBands; ++i) t[i] = exp(-bandExtinction(bandCoefficients(i), column));
}

void multipleAt(AtmosphereShape a, float r, float muS, out float psi[kSkyBands]) {
  vec2 xy = multipleTableCoordinates(a, r, muS);
  int c;
  vec2 f;
  bilinearTap(tableIndex(xy.x, kMultipleTableMu), tableIndex(xy.y, kMultipleTableR),
              kMultipleTableMu, kMultipleTableR, c, f);
  int c00 = c * kSkyBands, c01 = (c + 1) * kSkyBands;
  int c10 = (c + kMultipleTableMu) * kSkyBands, c11 = (c + kMultipleTableMu + 1) * kSkyBands;
  float w00 = (1.0f - f.y) * (1.0f - f.x), w01 = (1.0f - f.y) * f.x;
  float w10 = f.y * (1.0f - f.x), w11 = f.y * f.x;
  for (int i = 0; i < kSkyBands; ++i)
    psi[i] = w00 * multiple[c00 + i] + w01 * multiple[c01 + i] + w10 * multiple[c10 + i] +
             w11 * multiple[c11 + i];
}

// In-scattered radiance toward a point at radius r0 from direction d, per unit solar
// irradiance, and where the ray meets the ground, the ground's reflection (SkyModel::Tables::
// inscattered, step for step).
void inscattered(float r0, vec3 d, float albedo, bool withGround, out float l[kSkyBands]) {
  AtmosphereShape a = atmosphereShape();
  vec3 sun = sky.sunAndRadius.xyz;
  float mu = d.y, muS = sun.y, nu = dot(d, sun);
  bool ground = rayMeetsGround(r0, mu, a.bottomRadius);
  float len = ground ? distanceToGround(r0, mu, a.bottomRadius)
                     : distanceToSphereFar(r0, mu, a.topRadius);
  float phaseR = rayleighPhase(nu);
  float phaseM = cornetteShanksPhase(nu, sky.shape1.w);
  float throughput[kSkyBands];
  for (int i = 0; i < kSkyBands; ++i) {
    l[i] = 0.0f;
    throughput[i] = 1.0f;
  }
  const int kSteps = 40;
  float sunT[kSkyBands], psi[kSkyBands];
  for (int s = 0; s < kSteps && len > 0.0f; ++s) {
    vec2 step = quadraticStep(len, s, kSteps);
    vec2 rm = radiusAndCosineAfter(r0, mu, step.x);
    float muSt = sunCosineAfter(r0, muS, nu, step.x, rm.x);
    vec3 rho = constituentDensities(a, rm.x - a.bottomRadius);
    transmittanceToTop(a, rm.x, muSt, sunT);
    multipleAt(a, rm.x, muSt, psi);
    for (int i = 0; i < kSkyBands; ++i) {
      BandCoefficients c = bandCoefficients(i);
      float extinction = bandExtinction(c, rho);
      float stepT = exp(-extinction * step.y);
      l[i] += throughput[i] * bandInscatteringSource(c, rho, phaseR, phaseM, sunT[i], psi[i]) *
              stepIntegral(extinction, step.y, stepT);
      throughput[i] *= stepT;
    }
  }
  if (ground && withGround && albedo > 0.0f) {
    vec2 rm = radiusAndCosineAfter(r0, mu, len);
    float muSg = sunCosineAfter(r0, muS, nu, len, rm.x);
    transmittanceToTop(a, a.bottomRadius, muSg, sunT);
    for (int i = 0; i < kSkyBands; ++i)
      l[i] += throughput[i] * albedo / kPi * (sunT[i] * max(muSg, 0.0f) + sky.light[i].y);
  }
}
