#version 450
// One convolution pass of the direct / ring prefilter (convolvePass in src/bake/prefilter.cpp): per
// output direction n, the sums of L w and w over the source texels within the cap around n,
// w = lobe(n.l) x radial window(n.l) x texel solid angle. Each row of each face is searched only
// over the columns the cap reaches, as accumulateCap does.
#extension GL_GOOGLE_include_directive : require
#include "ibl/shared/brdf.h"
#include "ibl/shared/cube.h"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Source { vec4 dirOmega[]; };    // faces, rows, texels
layout(std430, binding = 1) readonly buffer Radiance { vec4 radiance[]; };
layout(std430, binding = 2) readonly buffer Targets { vec4 targets[]; };    // output directions
layout(std430, binding = 3) writeonly buffer Result { vec4 result[]; };     // sum of L w, sum of w
layout(push_constant) uniform Params {
  uint sourceSize, targetCount;
  uint kind;        // 0 cosine, 1 GGX, 2 GGX x visibility, 3 GGX x visibility x Fresnel
  uint windowMode;  // 0 none, 1 the outer edge, 2 both edges (a ring)
  float a2;         // alpha^2
  float outerLo, outerInv, innerLo, innerInv;
  float cosCap;     // <= 0: every texel
} params;

// The lobe as a function of c = n.l with n = v (ibl/shared/brdf.h, as the CPU's loops).
float lobe(float c) { return prefilterLobe(int(params.kind), c, params.a2); }

vec4 accumulate(vec3 n, uint begin, uint end, vec4 acc) {
  for (uint i = begin; i < end; ++i) {
    vec4 s = dirOmega[i];
    float c = max(dot(n, s.xyz), 0.0);
    float w = lobe(c) * s.w;
    if (params.windowMode >= 1u) w *= smoothRise(c, params.outerLo, params.outerInv);
    if (params.windowMode == 2u) w -= lobe(c) * s.w * smoothRise(c, params.innerLo, params.innerInv);
    acc += vec4(w * radiance[i].rgb, w);
  }
  return acc;
}

void main() {
  uint t = gl_GlobalInvocationID.x;
  if (t >= params.targetCount) return;
  vec3 n = targets[t].xyz;
  int size = int(params.sourceSize);
  vec4 acc = vec4(0.0);
  if (params.cosCap <= 0.0) {
    acc = accumulate(n, 0u, uint(6 * size * size), acc);
  } else {
    float k2 = params.cosCap * params.cosCap;
    float capAngle = acos(params.cosCap);
    for (int f = 0; f < 6; ++f) {
      vec3 a = faceAxis(f, 0), s = faceAxis(f, 1), tt = faceAxis(f, 2);
      float na = dot(n, a);
      if (acos(clamp(na, -1.0, 1.0)) > capAngle + 0.9553166) continue;  // out of reach
      float B = dot(n, s), nt = dot(n, tt);
      for (int row = 0; row < size; ++row) {
        // On this row, n.d >= k |d| with d = a + sc s + tc t is a quadratic inequality in sc.
        float tc = (float(row) + 0.5) * 2.0 / float(size) - 1.0;
        float A = na + tc * nt, Q = 1.0 + tc * tc;
        float qa = B * B - k2, qb = 2.0 * A * B, qc = A * A - k2 * Q;
        int x0 = 0, x1 = size - 1;
        if (qa < -1e-6) {
          float disc = qb * qb - 4.0 * qa * qc;
          if (disc < 0.0) continue;
          float root = sqrt(disc);
          float r1 = (-qb + root) / (2.0 * qa), r2 = (-qb - root) / (2.0 * qa);
          float lo = min(r1, r2), hi = max(r1, r2);
          if (hi < -1.0 - 1e-3 || lo > 1.0 + 1e-3) continue;
          float scale = 0.5 * float(size);
          x0 = max(0, int(floor((lo + 1.0) * scale - 0.5)) - 1);
          x1 = min(size - 1, int(ceil((hi + 1.0) * scale - 0.5)) + 1);
          if (x0 > x1) continue;
        }
        uint base = uint((f * size + row) * size);
        acc = accumulate(n, base + uint(x0), base + uint(x1) + 1u, acc);
      }
    }
  }
  result[t] = acc;
}
