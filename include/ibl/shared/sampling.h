// API: internal (may change without notice; math shared with the shaders)
// Low-discrepancy points, tangent frames and the importance sampling of BRDF lobes. C++ and
// GLSL (see lang.h): the bake, the reference renderer and the compute shaders use these.
#ifndef IBL_SHARED_SAMPLING_H
#define IBL_SHARED_SAMPLING_H
#include "ibl/shared/lang.h"

IBL_BEGIN

// The bits of x in reverse order.
IBL_FN uint reverseBits(uint x) {
  x = (x << 16u) | (x >> 16u);
  x = ((x & 0x00FF00FFu) << 8u) | ((x & 0xFF00FF00u) >> 8u);
  x = ((x & 0x0F0F0F0Fu) << 4u) | ((x & 0xF0F0F0F0u) >> 4u);
  x = ((x & 0x33333333u) << 2u) | ((x & 0xCCCCCCCCu) >> 2u);
  x = ((x & 0x55555555u) << 1u) | ((x & 0xAAAAAAAAu) >> 1u);
  return x;
}

// Van der Corput radical inverse in base 2 (the bit reversal of i), in [0, 1).
IBL_FN float radicalInverse2(uint i) {
  return float(reverseBits(i)) * 2.3283064365386963e-10f;  // 2^-32
}

// Point i of the n-point Hammersley set: (i / n, radicalInverse2(i)).
IBL_FN vec2 hammersley(uint i, uint n) {
  return vec2(float(i) / float(n), radicalInverse2(i));
}

// Point i of n spread evenly over the unit sphere, without randomness: the spherical Fibonacci
// points (Keinert et al. 2015, "Spherical Fibonacci Mapping", equation 2), z evenly spaced and
// the azimuth turning by the golden angle pi (3 - sqrt 5) from one point to the next.
IBL_FN vec3 sphericalFibonacciPoint(int i, int n) {
  float z = 1.0f - (2.0f * float(i) + 1.0f) / float(n);
  float phi = float(i) * kPi * (3.0f - sqrt(5.0f));
  float s = sqrt(max(0.0f, 1.0f - z * z));
  return vec3(s * cos(phi), s * sin(phi), z);
}

// Point of the unit disk, uniform in area: (sqrt(u1) cos 2 pi u2, sqrt(u1) sin 2 pi u2).
IBL_FN vec2 uniformDiskPoint(vec2 xi) {
  float r = sqrt(xi.x);
  float phi = 2.0f * kPi * xi.y;
  return vec2(r * cos(phi), r * sin(phi));
}

// Direction with pdf cos(theta) / pi in the tangent frame (Malley's method: a uniform disk
// point lifted to the hemisphere).
IBL_FN vec3 sampleCosineHemisphere(vec2 xi) {
  vec2 d = uniformDiskPoint(xi);
  return vec3(d.x, d.y, sqrt(max(0.0f, 1.0f - xi.x)));
}

// Half vector distributed with pdf D(h) (n.h) for GGX of parameter alpha, in the tangent frame
// (z = n). Walter et al. 2007, eq. 35-36: cos^2 theta = (1 - u) / (1 + (alpha^2 - 1) u).
IBL_FN vec3 sampleGgxHalfVector(vec2 xi, float alpha) {
  float a2 = alpha * alpha;
  float phi = 2.0f * kPi * xi.y;
  float cos2 = (1.0f - xi.x) / (1.0f + (a2 - 1.0f) * xi.x);
  float cosTheta = sqrt(cos2);
  float sinTheta = sqrt(max(0.0f, 1.0f - cos2));
  return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// Orthonormal basis whose third column is n (Duff et al. 2017, "Building an Orthonormal
// Basis, Revisited", JCGT 6(1), listing 3).
IBL_FN mat3 tangentFrame(vec3 n) {
  float s = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (s + n.z);
  float b = n.x * n.y * a;
  return mat3(vec3(1.0f + s * n.x * n.x * a, s * b, -s * n.x), vec3(b, s + n.y * n.y * a, -n.y), n);
}

// GGX normals visible from v (tangent frame, v.z > 0), distributed with pdf
// G1(v) max(0, v.h) D(h) / (n.v): Heitz 2018, "Sampling the GGX Distribution of Visible
// Normals", listing 1, anisotropic (alpha.x along x, alpha.y along y: the lobe's frame of
// brdf.h's GgxLobe). The part that depends on v alone is computed once.
struct VisibleNormalFrame {
  vec3 vh, t1, t2;  // the stretched view and a frame around it
  vec2 alpha;
  float s;
};
IBL_FN VisibleNormalFrame visibleNormalFrameAnisotropic(vec3 v, vec2 alpha) {
  VisibleNormalFrame f;
  f.vh = normalize(vec3(alpha.x * v.x, alpha.y * v.y, v.z));
  float lensq = f.vh.x * f.vh.x + f.vh.y * f.vh.y;
  f.t1 = lensq > 0.0f ? vec3(-f.vh.y, f.vh.x, 0.0f) / sqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
  f.t2 = cross(f.vh, f.t1);
  f.alpha = alpha;
  f.s = 0.5f * (1.0f + f.vh.z);
  return f;
}
IBL_FN VisibleNormalFrame visibleNormalFrame(vec3 v, float alpha) {
  return visibleNormalFrameAnisotropic(v, vec2(alpha));
}
// Warps a uniform disk point onto the projection of the visible hemisphere, lifts it and
// unstretches it. Reflecting v about the normal gives l with pdf G1 D / (4 n.v).
IBL_FN vec3 visibleNormalFromDisk(VisibleNormalFrame f, vec2 disk) {
  float p1 = disk.x;
  float p2 = (1.0f - f.s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + f.s * disk.y;
  vec3 nh = p1 * f.t1 + p2 * f.t2 + sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * f.vh;
  return normalize(vec3(f.alpha.x * nh.x, f.alpha.y * nh.y, max(0.0f, nh.z)));
}
IBL_FN vec3 sampleGgxVisibleNormalAnisotropic(vec3 v, vec2 xi, vec2 alpha) {
  return visibleNormalFromDisk(visibleNormalFrameAnisotropic(v, alpha), uniformDiskPoint(xi));
}
IBL_FN vec3 sampleGgxVisibleNormal(vec3 v, vec2 xi, float alpha) {
  return sampleGgxVisibleNormalAnisotropic(v, xi, vec2(alpha));
}

IBL_END

#endif
