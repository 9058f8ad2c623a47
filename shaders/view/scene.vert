#version 450
// The viewer's meshes: positions are already in world space (the scene applies node transforms).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "view/frame.glsl"
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec4 tangent;
layout(location = 3) in vec2 uv;
layout(location = 4) in vec2 uv1;
layout(location = 5) in vec4 color;  // COLOR_0, or white
layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec4 worldTangent;
layout(location = 3) out vec2 texCoord0;
layout(location = 4) out vec2 texCoord1;
layout(location = 5) out vec4 vertexColor;

void main() {
  worldPosition = position;
  worldNormal = normal;
  worldTangent = tangent;
  texCoord0 = uv;
  texCoord1 = uv1;
  vertexColor = color;
  gl_Position = frame.viewProjection * vec4(position, 1.0);
}
