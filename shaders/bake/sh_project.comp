#version 450
#extension GL_GOOGLE_include_directive : require
#include "ibl/shared/sh.h"
// SH9 projection (projectSh9 in src/math/sh.cpp): each workgroup sums L Y_lm omega over 64 texels
// in shared memory and writes one partial sum per coefficient; the host adds the partials in
// a fixed order.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Source { vec4 dirOmega[]; };
layout(std430, binding = 1) readonly buffer Radiance { vec4 radiance[]; };
layout(std430, binding = 2) writeonly buffer Partials { vec4 partials[]; };  // 9 per workgroup
layout(push_constant) uniform Params { uint sourceCount; } params;
shared vec3 sums[64][9];

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint local = gl_LocalInvocationID.x;
  vec3 l = vec3(0.0), d = vec3(0.0, 0.0, 1.0);
  if (i < params.sourceCount) {  // past the end: l = 0 adds nothing
    d = dirOmega[i].xyz;
    l = radiance[i].rgb * dirOmega[i].w;
  }
  for (int k = 0; k < 9; ++k) sums[local][k] = l * shBasis(k, d);
  barrier();
  for (uint stride = 32u; stride > 0u; stride >>= 1u) {
    if (local < stride)
      for (int k = 0; k < 9; ++k) sums[local][k] += sums[local + stride][k];
    barrier();
  }
  if (local == 0u)
    for (int k = 0; k < 9; ++k) partials[gl_WorkGroupID.x * 9u + uint(k)] = vec4(sums[0][k], 0.0);
}
