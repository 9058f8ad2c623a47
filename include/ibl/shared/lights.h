// Analytic lights in photometric units (Lagarde & de Rousiers 2014, "Moving Frostbite to
// Physically Based Rendering", section 4): the conversions from luminous power to intensity and
// luminance, the attenuation of punctual lights, and the illuminance of spheres and disks with
// the horizon handled. C++ and GLSL (see lang.h). Units: lm (luminous power), cd (intensity,
// lm/sr), lx (illuminance, lm/m^2), nit (luminance, cd/m^2); lengths in metres.
#ifndef IBL_SHARED_LIGHTS_H
#define IBL_SHARED_LIGHTS_H
#include "ibl/shared/lang.h"

IBL_BEGIN

// --- Luminous power to intensity (punctual) and luminance (area), Frostbite section 4.2 ---

// A point light emits power phi evenly over the sphere: I = phi / 4 pi (eq. 15).
IBL_FN float pointIntensityFromPower(float phi) {
  return phi / (4.0f * kPi);
}

// A spot light of outer half-angle theta_out: the physical conversion spreads phi over its cone,
// I = phi / (2 pi (1 - cos theta_out)) (eq. 16); Frostbite's own, I = phi / pi (eq. 17), keeps
// the brightness when the cone changes and loses the power's meaning.
IBL_FN float spotIntensityFromPower(float phi, float cosOuter, bool physical) {
  return physical ? phi / (2.0f * kPi * max(1.0f - cosOuter, 1e-6f)) : phi / kPi;
}

// Lambertian emitters: L = phi / (A pi) over the emitting area A (eqs. 18-21); sphere and tube
// emit from their whole surface, disk and rectangle from one side.
IBL_FN float sphereLuminanceFromPower(float phi, float radius) {
  return phi / (4.0f * kPi * radius * radius * kPi);
}
IBL_FN float diskLuminanceFromPower(float phi, float radius) {
  return phi / (kPi * radius * radius * kPi);
}
IBL_FN float tubeLuminanceFromPower(float phi, float radius, float length) {
  return phi / ((2.0f * kPi * radius * length + 4.0f * kPi * radius * radius) * kPi);
}
IBL_FN float rectLuminanceFromPower(float phi, float width, float height) {
  return phi / (width * height * kPi);
}

// --- Punctual attenuation, Frostbite section 4.7.1 (after Karis 2013) ---

// The smooth window that takes the inverse-square law to zero at the influence radius:
// saturate(1 - (d / radius)^4)^2, from d^2 and 1 / radius^2 (0: no window, always 1).
IBL_FN float smoothDistanceWindow(float squaredDistance, float invSquaredRadius) {
  float factor = squaredDistance * invSquaredRadius;
  float smoothFactor = clamp(1.0f - factor * factor, 0.0f, 1.0f);
  return smoothFactor * smoothFactor;
}

// 1 / d^2 (d at least 1 cm, a punctual light's size) times the window.
IBL_FN float distanceAttenuation(float squaredDistance, float invSquaredRadius) {
  return smoothDistanceWindow(squaredDistance, invSquaredRadius) /
         max(squaredDistance, 0.01f * 0.01f);
}

// A spot's angular falloff: 0 outside the outer cone, 1 inside the inner one, and between them
// the square of a linear ramp in cos(angle) (cosAngle: between the spot's direction and the
// direction from the light to the point).
IBL_FN float spotAngleAttenuation(float cosAngle, float cosInner, float cosOuter) {
  float scale = 1.0f / max(0.001f, cosInner - cosOuter);
  float t = clamp((cosAngle - cosOuter) * scale, 0.0f, 1.0f);
  return t * t;
}

// --- Sphere and disk illuminance, Frostbite section 4.7.2 ---

// The illuminance of a uniform spherical cap of luminance 1 (a sphere, or a disk facing the
// point) on a surface whose normal makes angle theta with the cap's center: pi sin^2(sigma)
// cos(theta) while the cap is all above the horizon, the exact integral of the cosine over the
// visible part of the cap while it straddles it (Snyder 1996's form factor, as Frostbite's
// Listing 9 writes it), 0 below. sinSigmaSqr: sin^2 of the cap's half-angle, r^2 / d^2 for a
// sphere. cosTheta is not clamped.
IBL_FN float illuminanceSphereOrDisk(float cosTheta, float sinSigmaSqr) {
  float illuminance;
  if (cosTheta * cosTheta > sinSigmaSqr) {
    illuminance = kPi * sinSigmaSqr * clamp(cosTheta, 0.0f, 1.0f);
  } else {
    float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
    float x = sqrt(1.0f / sinSigmaSqr - 1.0f);  // cot(sigma); d / r for a disk
    float y = -x * (cosTheta / sinTheta);
    float sinThetaSqrtY = sinTheta * sqrt(max(1.0f - y * y, 0.0f));
    illuminance = (cosTheta * acos(y) - x * sinThetaSqrtY) * sinSigmaSqr + atan(sinThetaSqrtY / x);
  }
  return max(illuminance, 0.0f);
}

// Illuminance per unit luminance of a sphere of radius r whose center is at `toLight` from the
// shaded point (normal n): exact, horizon included. The sphere may not reach the point.
IBL_FN float sphereIlluminanceFactor(vec3 n, vec3 toLight, float radius) {
  float squaredDistance = dot(toLight, toLight);
  float cosTheta = clamp(dot(n, toLight) / sqrt(squaredDistance), -1.0f, 1.0f);
  float sinSigmaSqr = min(radius * radius / squaredDistance, 0.9999f);
  return illuminanceSphereOrDisk(cosTheta, sinSigmaSqr);
}

// Illuminance per unit luminance of a one-sided disk of radius r centered at `toLight` from the
// shaded point, emitting along diskNormal: Frostbite's approximation, the disk treated as one
// facing the point (a cap of sin^2 sigma = r^2 / (r^2 + d^2)) and weighted by how much it faces
// the point, saturate(diskNormal . -l). Not exact: its error against quadrature is measured.
IBL_FN float diskIlluminanceFactor(vec3 n, vec3 toLight, float radius, vec3 diskNormal) {
  float squaredDistance = dot(toLight, toLight);
  vec3 l = toLight / sqrt(squaredDistance);
  float r2 = radius * radius;
  float sinSigmaSqr = r2 / (r2 + max(r2, squaredDistance));
  return illuminanceSphereOrDisk(dot(n, l), sinSigmaSqr) * clamp(dot(diskNormal, -l), 0.0f, 1.0f);
}

IBL_END

#endif
