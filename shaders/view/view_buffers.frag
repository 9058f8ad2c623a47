#version 450
// The view buffers of the screen-space ambient occlusion and reflections: each pixel's surface
// (the one the scene pass shades, view/surface.glsl) as its position and normal in the camera's
// view space (x right, y up, z forward) and its perceptual roughness, as the CPU's
// renderViewBuffers (src/render/view_buffers.cpp) computes them at the pixel centers.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "view/frame.glsl"
#include "ibl/shared/ambient_occlusion.h"
#include "ibl/shared/split_sum.h"
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec4 worldTangent;
layout(location = 3) in vec2 texCoord0;
layout(location = 4) in vec2 texCoord1;
layout(location = 5) in vec4 vertexColor;
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
#include "view/material.glsl"
#include "view/surface.glsl"

// World to the camera's view space.
vec3 toView(vec3 w) {
  return vec3(dot(w, normalize(frame.cameraRight.xyz)), dot(w, normalize(frame.cameraUp.xyz)),
              dot(w, frame.cameraForward.xyz));
}

void main() {
  // The triangle's plane, before fragmentSurface may discard (derivatives need every fragment).
  vec3 geometric = cross(dFdx(worldPosition), dFdy(worldPosition));
  // Single-sampled: the pixel center, as the CPU; the material's roughness as it is.
  ShadedSurface surface = fragmentSurface(1, false);
  if (draw.sphere.w > 0.0) geometric = surface.normal;  // traced: the sphere's own
  outPosition = vec4(toView(surface.position - frame.cameraPosition.xyz), 1.0);
  vec3 normal = viewBufferNormal(surface.normal, geometric, surface.view);
  outNormal = vec4(toView(normal), surface.material.roughness);
}
