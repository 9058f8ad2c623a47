// API: internal (may change without notice; math shared with the shaders)
// Real spherical harmonics, bands 0..2, with the normalization of Ramamoorthi & Hanrahan 2001
// ("An Efficient Representation for Irradiance Environment Maps", eq. 3), as polynomials of
// the world-frame direction (x, y, z). C++ and GLSL (see lang.h).
#ifndef IBL_SHARED_SH_H
#define IBL_SHARED_SH_H
#include "ibl/shared/lang.h"

IBL_BEGIN

// Basis function k of the order (l, m) = (0,0), (1,-1), (1,0), (1,1), (2,-2), (2,-1), (2,0),
// (2,1), (2,2) at a unit direction d.
IBL_FN float shBasis(int k, vec3 d) {
  float x = d.x, y = d.y, z = d.z;
  if (k == 0) return 0.282095f;
  if (k == 1) return 0.488603f * y;
  if (k == 2) return 0.488603f * z;
  if (k == 3) return 0.488603f * x;
  if (k == 4) return 1.092548f * x * y;
  if (k == 5) return 1.092548f * y * z;
  if (k == 6) return 0.315392f * (3.0f * z * z - 1.0f);
  if (k == 7) return 1.092548f * x * z;
  return 0.546274f * (x * x - y * y);
}

// The band l of coefficient k: 0 for k = 0, 1 for k = 1..3, 2 for k = 4..8.
IBL_FN int shBand(int k) {
  return k == 0 ? 0 : (k < 4 ? 1 : 2);
}

// Convolution of a band with the clamped cosine, A_l (R&H eq. 8): pi, 2 pi / 3, pi / 4.
IBL_FN float shCosineLobe(int band) {
  if (band == 0) return 3.14159265f;
  if (band == 1) return 2.09439510f;
  return 0.78539816f;
}

IBL_END

#endif
