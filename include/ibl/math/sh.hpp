#pragma once
// API: stable
// Real spherical harmonics, bands 0..2, with the normalization of Ramamoorthi & Hanrahan 2001
// ("An Efficient Representation for Irradiance Environment Maps"), as polynomials of the
// world-frame direction (x, y, z), +Y up. Coefficient order: (l, m) = (0,0), (1,-1), (1,0),
// (1,1), (2,-2), (2,-1), (2,0), (2,1), (2,2).
#include <array>

#include <glm/vec3.hpp>

#include "ibl/env/cubemap.hpp"
#include "ibl/shared/sh.h"

namespace ibl {

using Sh9 = std::array<glm::vec3, 9>;  // RGB coefficients, in the order above

// Defined once for C++ and GLSL in ibl/shared/sh.h: basis function k at a unit direction,
// the band of coefficient k, and the cosine lobe's A_l (R&H eq. 8).
using shared::shBand;
using shared::shBasis;
using shared::shCosineLobe;

// The nine basis functions at direction d, which must be unit (not normalized here).
std::array<float, 9> shBasis9(glm::vec3 d);

// Radiance coefficients L_lm = integral of L(w) Y_lm(w) dw, with exact texel solid angles:
// the radiance's units times sr. level must exist (not checked).
Sh9 projectSh9(const CubeMap& cube, int level = 0);

// Radiance reconstructed from the coefficients toward unit direction d (the radiance's units).
glm::vec3 evaluateSh9(const Sh9& sh, glm::vec3 d);

// Irradiance E(n) = sum A_l L_lm Y_lm(n) (R&H eq. 7) at unit normal n: radiance times sr
// (W/m^2 for radiance in W/(m^2 sr)); divide by pi for a white Lambertian surface's radiance.
glm::vec3 irradianceSh9(const Sh9& sh, glm::vec3 n);

// Multiplies band l by the Lanczos sigma factor sinc(l / 3) (1, 0.827, 0.414) to soften the
// ringing of bright lights (Sloan 2008, "Stupid Spherical Harmonics Tricks").
Sh9 windowSh9(const Sh9& sh);

// How the SH9 coefficients are windowed against ringing (`ibl bake --sh-window`).
enum class ShWindow {
  Off,      // exact projection (the default)
  Lanczos,  // windowSh9: the fixed sigma factors
  Cmgen,    // Filament cmgen's default, --sh-window=auto: cmgenShCutoff and cmgenShWindow
};

// A lower bound of the irradiance E(n) = sum A_l L_lm Y_lm(n) over every direction n, from the
// irradiance coefficients e_lm = A_l L_lm of one channel (Sloan 2017, "Deringing Spherical
// Harmonics", section 3: the band-1 direction turned onto z, the |m| = 2 part at its minimum
// over the azimuth, then the zonal and |m| = 1 parts minimized along z by Newton's method from
// z = -1/sqrt 2), evaluated as Filament's cmgen does (CubemapSH::windowSH, shmin).
float irradianceLowerBound(const std::array<float, 9>& e);

// The band factors of cmgen's window with cutoff w (in bands, > 0) for band l (0 to 2): 1 for
// l = 0, 0 for l >= w, else
// (sin x / x)^4 with x = pi l / w (a sinc applied four times).
float cmgenBandWindow(int l, float w);

// cmgen's --sh-window=auto cutoff: per channel, the largest w in [3, 13] found by bisection to
// 0.1 bands (at most 16 halvings, the upper end starting at the previous channels' result) for
// which irradianceLowerBound of the windowed coefficients is >= 0; the smallest over R, G, B.
// `radiance`: the radiance coefficients L_lm.
float cmgenShCutoff(const Sh9& radiance);

// The coefficients windowed as `window` says; `factors`, if given, receives the factor of each
// band (1, 1, 1 when off). radiance: the coefficients L_lm of projectSh9.
Sh9 windowSh9(const Sh9& radiance, ShWindow window, std::array<float, 3>* factors = nullptr);

// The coefficients with band l multiplied by bandFactors[l] (a window chosen before).
Sh9 windowSh9(const Sh9& sh, const std::array<float, 3>& bandFactors);

}  // namespace ibl
