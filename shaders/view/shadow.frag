#version 450
// The shadow maps' pass: each texel stores the depth of the first surface along its ray that
// transmits nothing, as the CPU's ShadowMapBuilder traces it (src/render/shadows.cpp): the
// rasterizer samples texel centers, the surface's own depth is written (shadowStoredDepth), the
// material's alpha masks what it does not cover, and a sphere is ray traced in its bounding
// polyhedron along the texel's ray. In the filter's draw (kShadowFilterPass), the surfaces that
// transmit in front of that depth each multiply the texel's color by what they let through
// (shadowMapCrossing, at the geometric normal) and keep the nearest stored depth in its alpha
// (the pipeline blends multiply and min).
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

const int kShadowFilterPass = 5;  // ScenePass in src/gpu/scene_upload.hpp

void main() {
  ShadowLayer l = shadowLayerAt(draw.shadowLayer);
  float z = dot(worldPosition - l.origin, l.forward);
  vec3 d = shadowRayDirection(l, gl_FragCoord.xy, shadowMapSize());
  // The triangle's own normal (before any fragment of the quad is discarded).
  float cosine = dot(normalize(cross(dFdx(worldPosition), dFdy(worldPosition))), normalize(d));
  if (draw.sphere.w > 0.0) {
    float len = length(d);
    Ray ray = Ray(shadowRayOrigin(l, gl_FragCoord.xy, shadowMapSize()), d / len);
    float t = intersectSphere(ray, draw.sphere);
    // The filter's draw sees a sphere once, through the polyhedron's faces in front of it (the
    // way out crosses it at the same angle as the way in).
    if (t < 0.0 || (draw.scenePass == kShadowFilterPass && z > t / len)) discard;
    z = t / len;  // d's forward component is 1 (orthographic: d is forward)
    cosine = dot(normalize(ray.origin + t * ray.direction - draw.sphere.xyz), ray.direction);
  } else if (!materialCovers()) {
    discard;
  }
  gl_FragDepth = shadowStoredDepth(l, z);
  if (draw.scenePass == kShadowFilterPass) {
    vec3 passed = shadowMapCrossing(fragmentMaterial(), cosine);
    if (draw.sphere.w > 0.0) passed *= passed;
    filterColor = vec4(passed, gl_FragDepth);
    // Tested a little nearer: a surface at the depth's own (a glass resting on a table) is in
    // front of it, as crossTransmissive (src/render/ray_tracer.hpp) counts it.
    gl_FragDepth = max(gl_FragDepth - 1e-5, 0.0);
  } else {
    filterColor = vec4(1.0);
  }
}
