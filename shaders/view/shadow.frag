#version 450
// The shadow maps' depths: each texel stores the depth of the first surface along its ray that
// transmits nothing (view/shadow.glsl; ShadowPass draws the meshes of kShadowPass).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "view/frame.glsl"
#include "view/shadow_maps.glsl"
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec2 texCoord0;
layout(location = 2) in vec2 texCoord1;
layout(location = 3) in vec4 vertexColor;
#include "view/material.glsl"
#include "view/shadow.glsl"

void main() {
  vec3 passed;
  gl_FragDepth = shadowFragmentDepth(false, passed);
}
