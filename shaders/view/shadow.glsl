// The shadow maps' fragments (view/shadow.frag, the depths; view/shadow_filter.frag, the filters
// of the surfaces that transmit), as the CPU's ShadowMapBuilder traces them
// (src/render/shadows.cpp): the rasterizer samples texel centers, the surface's own depth is
// stored (shadowStoredDepth), the material's alpha masks what it does not cover, and a sphere is
// ray traced in its bounding polyhedron along the texel's ray. Needs view/frame.glsl,
// view/shadow_maps.glsl, the inputs worldPosition, texCoord0, texCoord1 and vertexColor, and
// view/material.glsl.

// The stored depth of this fragment's surface in the layer drawn (discarded where it has none),
// and with `filtered` what it lets through (shadowMapCrossing at its geometric normal; a
// sphere's two crossings, at the same angle, in one fragment: those of the polyhedron's faces
// behind the sphere are discarded).
float shadowFragmentDepth(bool filtered, out vec3 passed) {
  ShadowLayer l = shadowLayerAt(draw.shadowLayer);
  float z = dot(worldPosition - l.origin, l.forward);
  vec3 d = shadowRayDirection(l, gl_FragCoord.xy, shadowMapSize());
  // The triangle's own normal (before any fragment of the quad is discarded).
  float cosine = dot(normalize(cross(dFdx(worldPosition), dFdy(worldPosition))), normalize(d));
  if (draw.sphere.w > 0.0) {
    float len = length(d);
    Ray ray = Ray(shadowRayOrigin(l, gl_FragCoord.xy, shadowMapSize()), d / len);
    float t = intersectSphere(ray, draw.sphere);
    if (t < 0.0 || (filtered && z > t / len)) discard;
    z = t / len;  // d's forward component is 1 (orthographic: d is forward)
    cosine = dot(normalize(ray.origin + t * ray.direction - draw.sphere.xyz), ray.direction);
  } else if (!materialCovers()) {
    discard;
  }
  passed = vec3(1.0);
  if (filtered) {
    passed = shadowMapCrossing(fragmentMaterial(), cosine);
    if (draw.sphere.w > 0.0) passed *= passed;
  }
  return shadowStoredDepth(l, z);
}
