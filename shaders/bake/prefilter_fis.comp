#version 450
// One specular level by filtered importance sampling (prefilterLevelSampled in
// src/bake/prefilter.cpp): the host's sample set (tangent-frame directions, source lods, weights),
// rotated into each texel's frame and read with seam-aware trilinear lookups.
#extension GL_GOOGLE_include_directive : require
#include "ibl/shared/cube.h"
#include "ibl/shared/sampling.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) readonly buffer Source { vec4 texels[]; };  // every level
layout(std430, binding = 1) readonly buffer Levels { uvec2 levels[]; };  // (size, first texel)
layout(std430, binding = 2) readonly buffer Samples { vec4 samples[]; };  // (l, lod), then (weight)
layout(std430, binding = 3) writeonly buffer Result { vec4 result[]; };
layout(push_constant) uniform Params { uint size; uint sampleCount; uint levelCount; } params;

#include "env/cube_buffer.glsl"

vec3 sampleTrilinear(float lod, vec3 dir) {
  lod = clamp(lod, 0.0, float(params.levelCount - 1u));
  int l0 = int(floor(lod));
  int l1 = min(l0 + 1, int(params.levelCount) - 1);
  float w = lod - float(l0);
  vec3 a = sampleBilinear(l0, dir);
  if (w == 0.0 || l1 == l0) return a;
  return a * (1.0 - w) + sampleBilinear(l1, dir) * w;
}

void main() {
  uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y, face = gl_GlobalInvocationID.z;
  uint n = params.size;
  if (x >= n || y >= n) return;
  mat3 frame = tangentFrame(texelDirection(int(face), int(x), int(y), int(n)));
  vec3 sum = vec3(0.0);
  float wsum = 0.0;
  for (uint k = 0u; k < params.sampleCount; ++k) {
    vec4 s = samples[2u * k];
    float w = samples[2u * k + 1u].x;
    sum += sampleTrilinear(s.w, frame * s.xyz) * w;
    wsum += w;
  }
  result[(face * n + y) * n + x] = vec4(wsum > 0.0 ? sum / wsum : vec3(0.0), 1.0);
}
