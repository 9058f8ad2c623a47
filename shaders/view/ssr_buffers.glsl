// The screen-space reflections' inputs for ibl/shared/screen_space_reflections.h, shared by the
// trace (view/ssr.frag) and the resolve (view/ssr_resolve.frag): the view buffers, the lit frame
// and the traced reflection read by texelFetch, and the parameters from the frame's uniforms
// (SceneRenderer passes reflectionParameters of the options, as the CPU computes them).
vec3 ssrViewPosition(ivec2 t) {
  return texelFetch(viewPositions, t, 0).xyz;
}
vec3 ssrViewNormal(ivec2 t) {
  return texelFetch(viewNormals, t, 0).xyz;
}
vec3 ssrRadiance(ivec2 t) {
  return texelFetch(litFrame, t, 0).rgb;
}
float ssrRoughness(ivec2 t) {  // the normal buffer's w
  return texelFetch(viewNormals, t, 0).w;
}
vec4 ssrTraced(ivec2 t) {
  return texelFetch(tracedReflection, t, 0);
}
#include "ibl/shared/screen_space_reflections.h"

ScreenProjection frameScreenProjection() {
  ScreenProjection s;
  s.size = frame.viewport.xy;
  s.scale = frame.projection.xy;
  s.perspective = frame.projection.z;
  return s;
}

ReflectionParameters frameReflectionParameters() {
  ReflectionParameters r;
  r.maxDistance = frame.reflectionMarch.x;
  r.thickness = frame.reflectionMarch.y;
  r.stride = frame.reflectionMarch.z;
  r.maxSteps = int(frame.reflectionMarch.w);
  r.rays = int(frame.reflectionLobe.x);
  r.fadeStart = frame.reflectionLobe.y;
  r.fadeEnd = frame.reflectionLobe.z;
  r.edgeFade = frame.reflectionLobe.w;
  return r;
}
