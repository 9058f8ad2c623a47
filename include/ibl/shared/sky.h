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

IBL_END

#endif
