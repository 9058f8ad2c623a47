#version 450
// Screen-space ambient occlusion of the viewer: GTAO (ibl/shared/ambient_occlusion.h, which the
// CPU's split sum runs too) at each pixel from the view buffers (view/view_buffers.frag). Writes
// the visibility and the bent normal in world space, read by view/scene.frag.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "view/frame.glsl"
layout(location = 0) out vec4 outOcclusion;

vec3 aoViewPosition(ivec2 t) {
  return texelFetch(viewPositions, t, 0).xyz;
}
#include "ibl/shared/ambient_occlusion.h"

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 normal = texelFetch(viewNormals, pixel, 0);
  ScreenProjection s;
  s.size = frame.viewport.xy;
  s.scale = frame.projection.xy;
  s.perspective = frame.projection.z;
  AmbientOcclusionParameters a;
  a.radius = frame.ambientOcclusion.x;
  a.falloff = frame.ambientOcclusion.y;
  a.slices = int(frame.ambientOcclusion.z);
  a.steps = int(frame.ambientOcclusion.w);
  AmbientOcclusion ao = groundTruthAmbientOcclusion(s, pixel, normal.xyz, a);
  vec3 bent = ao.bentNormal.x * normalize(frame.cameraRight.xyz) +
              ao.bentNormal.y * normalize(frame.cameraUp.xyz) +
              ao.bentNormal.z * frame.cameraForward.xyz;
  outOcclusion = vec4(ao.visibility, texelFetch(viewPositions, pixel, 0).w > 0.0 ? bent : vec3(0.0));
}
