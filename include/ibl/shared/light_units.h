// API: internal (may change without notice; math shared with the shaders)
// Analytic lights in photometric units (Lagarde & de Rousiers 2014, "Moving Frostbite to
// Physically Based Rendering", section 4): the conversions from luminous power to intensity and
// luminance, and the attenuation of punctual lights (the distance window, the spot's cone), which
// the real-time shading (lights.h) and the reference (light_sampling.h) both apply. C++ and GLSL
// (see lang.h). Units: lm (luminous power), cd (intensity, lm/sr), lx (illuminance, lm/m^2), nit
// (luminance, cd/m^2); lengths in metres.
#ifndef IBL_SHARED_LIGHT_UNITS_H
#define IBL_SHARED_LIGHT_UNITS_H
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

IBL_END

#endif
