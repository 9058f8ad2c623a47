#pragma once
// Real spherical harmonics, bands 0..2, with the normalization of Ramamoorthi & Hanrahan 2001
// ("An Efficient Representation for Irradiance Environment Maps"), as polynomials of the
// world-frame direction (x, y, z), +Y up. Coefficient order: (l, m) = (0,0), (1,-1), (1,0),
// (1,1), (2,-2), (2,-1), (2,0), (2,1), (2,2).
#include <array>

#include <glm/vec3.hpp>

#include "ibl/env/cubemap.hpp"
#include "ibl/shared/sh.h"

namespace ibl {

using Sh9 = std::array<glm::vec3, 9>;  // RGB coefficients

// Defined once for C++ and GLSL in ibl/shared/sh.h: basis function k at a unit direction,
// the band of coefficient k, and the cosine lobe's A_l (R&H eq. 8).
using shared::shBand;
using shared::shBasis;
using shared::shCosineLobe;

// The nine basis functions at a unit direction.
std::array<float, 9> shBasis9(glm::vec3 d);

// Radiance coefficients L_lm = integral of L(w) Y_lm(w) dw, with exact texel solid angles.
Sh9 projectSh9(const CubeMap& cube, int level = 0);

// Radiance reconstructed from the coefficients.
glm::vec3 evaluateSh9(const Sh9& sh, glm::vec3 d);

// Irradiance E(n) = sum A_l L_lm Y_lm(n) (R&H eq. 7).
glm::vec3 irradianceSh9(const Sh9& sh, glm::vec3 n);

// Multiplies band l by the Lanczos sigma factor sinc(l / 3) (1, 0.827, 0.414) to soften the
// ringing of bright lights (Sloan 2008, "Stupid Spherical Harmonics Tricks").
Sh9 windowSh9(const Sh9& sh);

}  // namespace ibl
