#version 450
// The shadow maps' pass: the meshes drawn into one layer of a light's shadow map (the layer in
// the push constants), through the layer's light space (shadowClipPosition in
// ibl/shared/shadows.h).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "view/frame.glsl"
#include "view/shadow_maps.glsl"
layout(location = 0) in vec3 position;
layout(location = 3) in vec2 uv;
layout(location = 4) in vec2 uv1;
layout(location = 5) in vec4 color;
layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec2 texCoord0;
layout(location = 2) out vec2 texCoord1;
layout(location = 3) out vec4 vertexColor;
layout(push_constant) uniform Layer {
  layout(offset = 16) int shadowLayer;  // DrawConstants::shadowLayer
} pass;

void main() {
  worldPosition = position;
  texCoord0 = uv;
  texCoord1 = uv1;
  vertexColor = color;
  gl_Position = shadowClipPosition(shadowLayerAt(pass.shadowLayer), position);
}
