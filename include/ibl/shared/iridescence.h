// API: internal (may change without notice; math shared with the shaders)
// KHR_materials_iridescence: the Fresnel reflectance of a thin dielectric film over the base
// material (Belcour & Barla 2017, "A Practical Extension to Microfacet Theory for the Modeling of
// Varying Iridescence", section 4, as the extension's implementation notes give it: Schlick's
// Fresnel at both interfaces, phase shifts of 0 or pi, the Airy series to its second harmonic
// and the spectral integration in closed form through Gaussian fits of the CIE 1931 observer).
// C++ and GLSL (see lang.h).
#ifndef IBL_SHARED_IRIDESCENCE_H
#define IBL_SHARED_IRIDESCENCE_H
#include "ibl/shared/brdf.h"
#include "ibl/shared/lang.h"

IBL_BEGIN

// The reflectance at normal incidence between media of indices `transmitted` and `incident`:
// ((t - i) / (t + i))^2.
IBL_FN vec3 reflectanceAtNormalIncidence(vec3 transmitted, float incident) {
  vec3 r = (transmitted - vec3(incident)) / (transmitted + vec3(incident));
  return r * r;
}

// The real index of refraction (from air) whose reflectance at normal incidence is f0, the
// inverse of the above: (1 + sqrt f0) / (1 - sqrt f0). A metal's extinction is taken as 0, as
// the extension does.
IBL_FN vec3 iorFromReflectance(vec3 f0) {
  vec3 s = sqrt(clamp(f0, vec3(0.0f), vec3(0.9999f)));
  return (vec3(1.0f) + s) / (vec3(1.0f) - s);
}

// The spectral sensitivity's Fourier transform at optical path difference opd (nm) and phase
// shift `shift` (per channel), in linear Rec. 709: the CIE 1931 matching functions integrated
// against cos(2 pi opd / lambda + shift) over wavelength, divided by the integral of y-bar
// (the extension's evalSensitivity: one Gaussian per function, two for x-bar).
IBL_FN vec3 thinFilmSensitivity(float opd, vec3 shift) {
  float phase = 2.0f * kPi * opd * 1.0e-9f;
  vec3 val = vec3(5.4856e-13f, 4.4201e-13f, 5.2481e-13f);
  vec3 pos = vec3(1.6810e+06f, 1.7953e+06f, 2.2084e+06f);
  vec3 var = vec3(4.3278e+09f, 9.3046e+09f, 6.6121e+09f);
  vec3 xyz = val * sqrt(2.0f * kPi * var) * cos(pos * phase + shift) * exp(-phase * phase * var);
  xyz.x += 9.7470e-14f * sqrt(2.0f * kPi * 4.5282e+09f) * cos(2.2399e+06f * phase + shift.x) *
           exp(-4.5282e+09f * phase * phase);
  xyz /= 1.0685e-7f;
  // CIE XYZ to linear Rec. 709 (columns).
  mat3 toRec709 = mat3(3.2404542f, -0.9692660f, 0.0556434f, -1.5371385f, 1.8760108f, -0.2040259f,
                       -0.4985314f, 0.0415560f, 1.0572252f);
  return toRec709 * xyz;
}

// The reflectance of a thin film of index filmIor and thickness (nm) over a base of normal-
// incidence reflectance baseF0, seen from a medium of index outsideIor at cos theta1 = cosine
// (the microfacet's v.h): the extension's iridescent_fresnel. The optical path difference is
// 2 filmIor thickness cos theta2, theta2 the angle refracted into the film (Belcour & Barla's
// equation 4 and their code, and the glTF Sample Viewer; the extension's text writes cos theta1).
// A film of no thickness takes the outside's index, so that it vanishes (as the Sample Viewer
// does). Total internal reflection in the film reflects everything.
IBL_FN vec3 thinFilmFresnel(float outsideIor, float filmIor, float thickness, float cosine,
                            vec3 baseF0) {
  float eta = mix(outsideIor, filmIor, clamp(thickness / 0.03f, 0.0f, 1.0f));
  float c1 = clamp(cosine, 0.0f, 1.0f);
  float sin2Sq = (outsideIor / eta) * (outsideIor / eta) * (1.0f - c1 * c1);
  if (sin2Sq >= 1.0f) return vec3(1.0f);
  float c2 = sqrt(1.0f - sin2Sq);
  // The outside-film interface: Schlick's Fresnel, the phase pi where the film is the lower index.
  float r12 = reflectanceAtNormalIncidence(vec3(eta), outsideIor).x;
  float R12 = r12 + (1.0f - r12) * schlickWeight(c1);
  float T121 = 1.0f - R12;
  float phi12 = eta < outsideIor ? kPi : 0.0f;
  float phi21 = kPi - phi12;
  // The film-base interface, per channel.
  vec3 baseIor = iorFromReflectance(baseF0 + vec3(0.0001f));
  vec3 r23 = reflectanceAtNormalIncidence(baseIor, eta);
  vec3 R23 = r23 + (vec3(1.0f) - r23) * schlickWeight(c2);
  vec3 phi23 = vec3(baseIor.x < eta ? kPi : 0.0f, baseIor.y < eta ? kPi : 0.0f,
                    baseIor.z < eta ? kPi : 0.0f);
  vec3 phi = vec3(phi21) + phi23;
  float opd = 2.0f * eta * thickness * c2;
  // The Airy series: the incoherent sum (m = 0), then the first two harmonics.
  vec3 R123 = clamp(R12 * R23, vec3(1e-5f), vec3(0.9999f));
  vec3 r123 = sqrt(R123);
  vec3 Rs = T121 * T121 * R23 / (vec3(1.0f) - R123);
  vec3 reflectance = vec3(R12) + Rs;
  vec3 cm = Rs - vec3(T121);
  for (int m = 1; m <= 2; ++m) {
    cm *= r123;
    reflectance += cm * 2.0f * thinFilmSensitivity(float(m) * opd, float(m) * phi);
  }
  return max(reflectance, vec3(0.0f));
}

IBL_END

#endif
