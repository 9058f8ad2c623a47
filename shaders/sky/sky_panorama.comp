#version 450
// The sky's panorama from the sky-view table, one pixel per invocation (SkyModel::panorama).
layout(local_size_x = 8, local_size_y = 8) in;
#include "ibl/shared/cube.h"
#include "ibl/shared/sky.h"
layout(std430, binding = 0) readonly buffer View { vec4 view[]; };  // [half][row][azimuth]
layout(std430, binding = 1) writeonly buffer Pixels { vec4 pixels[]; };
layout(push_constant) uniform Params {
  vec4 sunAndHorizon;  // the direction toward the sun; the horizon's elevation
  uint width;
  uint height;
} params;

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= params.width || p.y >= params.height) return;
  vec3 d = equirectToDirection((float(p.x) + 0.5f) / float(params.width),
                               (float(p.y) + 0.5f) / float(params.height));
  vec3 c = skyViewCoordinates(params.sunAndHorizon.w, params.sunAndHorizon.xyz, d);
  float x = tableIndex(c.x, kSkyViewAzimuths), y = tableIndex(c.y, kSkyViewRows);
  int x0 = min(int(x), kSkyViewAzimuths - 2);
  int y0 = min(int(y), kSkyViewRows - 2);
  vec2 f = vec2(x - float(x0), y - float(y0));
  int i = (int(c.z) * kSkyViewRows + y0) * kSkyViewAzimuths + x0;
  vec3 v = mix(mix(view[i].rgb, view[i + 1].rgb, f.x),
               mix(view[i + kSkyViewAzimuths].rgb, view[i + kSkyViewAzimuths + 1].rgb, f.x), f.y);
  pixels[p.y * params.width + p.x] = vec4(v, 1.0f);
}
