#version 450
// The shadow maps' pass: each texel stores the depth of the first surface along its ray, as the
// CPU's ShadowMapBuilder traces it (src/render/shadows.cpp): the rasterizer samples texel
// centers, the surface's own depth is written (shadowStoredDepth), the material's alpha masks
// what it does not cover, and a sphere is ray traced in its bounding polyhedron along the
// texel's ray.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "view/frame.glsl"
#include "view/shadow_maps.glsl"
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec2 texCoord0;
layout(location = 2) in vec2 texCoord1;
layout(location = 3) in vec4 vertexColor;
#include "view/material.glsl"

void main() {
  ShadowLayer l = shadowLayerAt(draw.shadowLayer);
  float z = dot(worldPosition - l.origin, l.forward);
  if (draw.sphere.w > 0.0) {
    vec3 d = shadowRayDirection(l, gl_FragCoord.xy, shadowMapSize());
    float len = length(d);
    float t = intersectSphere(Ray(shadowRayOrigin(l, gl_FragCoord.xy, shadowMapSize()), d / len),
                              draw.sphere);
    if (t < 0.0) discard;
    z = t / len;  // d's forward component is 1 (orthographic: d is forward)
  } else if (!materialCovers()) {
    discard;
  }
  gl_FragDepth = shadowStoredDepth(l, z);
}
