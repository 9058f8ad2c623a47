#version 450
// The sky-view table, one texel per invocation: the radiance over the bands, as linear Rec.709
// in cd/m^2 (SkyModel::Tables::buildSkyView).
layout(local_size_x = 64) in;
#include "ibl/shared/color.h"
#include "sky/atmosphere.glsl"
layout(std430, binding = 3) writeonly buffer View { vec4 view[]; };  // [half][row][azimuth]

void main() {
  int k = int(gl_GlobalInvocationID.x);
  if (k >= 2 * kSkyViewRows * kSkyViewAzimuths) return;
  vec3 d = skyViewTexelDirection(sky.flags.x, sky.sunAndRadius.xyz, k / kSkyViewAzimuths,
                                 k % kSkyViewAzimuths);
  float l[kSkyBands];
  inscattered(sky.sunAndRadius.w, d, sky.shape1.z, true, l);
  vec3 xyzSum = vec3(0.0f);
  for (int i = 0; i < kSkyBands; ++i) xyzSum += l[i] * sky.light[i].x * sky.xyz[i].xyz;
  view[k] = vec4(max(xyzToLinearRec709(xyzSum), vec3(0.0f)), 1.0f);
}
