#version 450
// The shadow maps' filters (ShadowPass draws the meshes of kShadowFilterPass after the depths):
// the surfaces that transmit in front of a texel's depth each multiply its color by what they
// let through and keep the least stored depth in its alpha (the pipeline blends multiply and
// min), as the CPU's ShadowMapBuilder traces them.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "view/frame.glsl"
#include "view/shadow_maps.glsl"
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec2 texCoord0;
layout(location = 2) in vec2 texCoord1;
layout(location = 3) in vec4 vertexColor;
layout(location = 0) out vec4 filterColor;
#include "view/material.glsl"
#include "view/shadow.glsl"

void main() {
  vec3 passed;
  float depth = shadowFragmentDepth(true, passed);
  filterColor = vec4(passed, depth);
  // Tested a little nearer: a surface at the depth's own (a glass resting on a table) is in
  // front of it, as crossTransmissive (src/render/ray_tracer.hpp) counts it.
  gl_FragDepth = max(depth - 1e-5, 0.0);
}
