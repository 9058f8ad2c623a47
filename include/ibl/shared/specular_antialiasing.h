// API: internal (may change without notice; math shared with the shaders)
// Specular antialiasing: a GGX lobe widened by how much the shading normal turns across a pixel
// and by the spread of the normal map's detail a filtered texel averaged, so that a highlight
// narrower than the pixel is filtered instead of sampled. The CPU split sum
// (renderRays, src/render/renderer.cpp) takes the normal's change from rays one pixel over; the
// viewer (shaders/view/surface.glsl) from the fragment's screen derivatives. C++ and GLSL (see
// lang.h).
#ifndef IBL_SHARED_SPECULAR_ANTIALIASING_H
#define IBL_SHARED_SPECULAR_ANTIALIASING_H
#include "ibl/shared/lang.h"

IBL_BEGIN

// The variance of the pixel's filter in pixels squared: a box one pixel wide, 1 / 12, the filter
// that multisampling's resolve and a supersampled render apply. (Tokuyoshi & Kaplanyan 2019,
// "Improved Geometric Specular Antialiasing" (I3D), Listing 1, take a Gaussian of variance 1/4,
// three times the box's, which measured farther from the supersampled render: docs/render.md.)
// And the largest widening of alpha^2 (their kappa), which keeps a sharp crease or a silhouette
// from turning the whole pixel rough.
const float kSpecularFilterVariance = 1.0f / 12.0f;
const float kSpecularKernelMaxAlpha2 = 0.18f;

// How far from 1 the length of an 8-bit normal texel's unit vector may decode: each channel
// rounds by up to half a code, 1 / 255 in [-1, 1], along a unit normal at most sqrt(3) / 255.
const float kNormalTexelLengthTolerance = 0.0068f;

// The alpha^2 of the spread of normals that a filtered normal-map texel averaged (a mip level's,
// or a bilinear blend of texels of different directions): the shorter the mean, the wider the
// spread. With the normals as a von Mises-Fisher distribution, a mean of length r has
// concentration kappa = (3r - r^3) / (1 - r^2) (Banerjee et al. 2005, equation 4.4, the fit the
// normal-map filtering of Han et al. 2007 uses), slopes of variance 1 / kappa per axis, and
// alpha^2 = 2 / kappa as the geometric term below. texel: the normal texture's RGB in [0, 1];
// scale: the map's (glTF normalTexture.scale), which scales the slopes. A texel as long as a
// rounded unit normal (kNormalTexelLengthTolerance) spreads nothing: full-resolution texels, and
// the CPU renderer's, which reads no mip levels. The tolerance is the worst rounding's (a typical
// one is a third of it), so a spread below alpha^2 = 0.0136 goes unseen: the price of never
// widening a map that has none.
IBL_FN float normalMapAlpha2(vec3 texel, float scale) {
  float r = length(texel * 2.0f - 1.0f) + kNormalTexelLengthTolerance;
  if (r >= 1.0f) return 0.0f;
  return min(2.0f * (1.0f - r * r) / (3.0f * r - r * r * r) * scale * scale, 1.0f);
}

// The perceptual roughness of the lobe filtered over the pixel. mapAlpha2: the spread of the
// normal map's detail within the texel read (normalMapAlpha2; 0 without a map). dndx, dndy: the
// shading normal one pixel over in x and in y, minus this one's; their change across the pixel
// is a variance of slopes sigma^2 = kSpecularFilterVariance (|dndx|^2 + |dndy|^2), and a lobe of
// alpha^2 convolved with it has alpha^2 + 2 sigma^2 (Tokuyoshi & Kaplanyan 2019, equation 8),
// the widening clamped to kSpecularKernelMaxAlpha2. Both add to alpha^2 = roughness^4, not to
// the perceptual roughness. Non-finite differences (a quad whose neighbor left the surface)
// widen nothing; they are told by their exponent bits, since a shader compiler may assume none
// exist.
IBL_FN float specularAntialiasedRoughness(float roughness, float mapAlpha2, vec3 dndx, vec3 dndy) {
  float variance = kSpecularFilterVariance * (dot(dndx, dndx) + dot(dndy, dndy));
  if ((IBL_FLOAT_BITS(variance) & 0x7f800000u) == 0x7f800000u) variance = 0.0f;
  float kernel = min(2.0f * variance, kSpecularKernelMaxAlpha2);
  float alpha2 = roughness * roughness * roughness * roughness;
  return sqrt(sqrt(min(alpha2 + mapAlpha2 + kernel, 1.0f)));
}

IBL_END

#endif
