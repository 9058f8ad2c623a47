#version 450
// The sky's light on the ground, one cell of the hemisphere (ring, sector) per invocation; the
// host adds the cells up in order (SkyModel::Tables::buildGroundSky).
layout(local_size_x = 64) in;
#include "sky/atmosphere.glsl"
layout(std430, binding = 3) writeonly buffer Cells { float cells[]; };  // [cell][band]

void main() {
  int k = int(gl_GlobalInvocationID.x);
  if (k >= kGroundSkyRings * kGroundSkySectors) return;
  vec4 d = groundSkyDirection(k / kGroundSkySectors, k % kGroundSkySectors);
  float l[kSkyBands];
  inscattered(sky.shape0.x, d.xyz, 0.0f, false, l);
  for (int i = 0; i < kSkyBands; ++i) cells[k * kSkyBands + i] = l[i] * d.w;
}
