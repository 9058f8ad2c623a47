// The shadow maps' fragments (view/shadow.frag, the depths; view/shadow_filter.frag, the filters
// of the surfaces that transmit), as the CPU's ShadowMapBuilder traces them
// (src/render/shadows.cpp): the rasterizer samples texel centers, the surface's own depth is
// stored (shadowStoredDepth), the material's alpha masks what it does not cover, and a sphere is
// ray traced in its bounding polyhedron along the texel's ray. Needs view/frame.glsl,
// view/shadow_maps.glsl, the inputs worldPosition, texCoord0, texCoord1 and vertexColor, and
// view/material.glsl.

// The stored depth of this fragment's surface in the layer drawn (discarded where it has none),
// and with `filtered` what it lets through (shadowMapCrossing at its geometric normal). A
// sphere's surface along the texel's ray: the first (the depths); with `filtered`, the way in
// where the polyhedron's face lies in front of the sphere and the way out where it lies behind,
// each a crossing tested against the depths on its own, as the CPU crosses them.
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
    if (filtered) {
      vec3 oc = ray.origin - draw.sphere.xyz;
      float b = dot(oc, ray.direction);
      float disc = b * b - dot(oc, oc) + draw.sphere.w * draw.sphere.w;
      float s = sqrt(max(disc, 0.0));
      t = disc < 0.0 ? -1.0 : (z * len < -b ? -b - s : -b + s);  // d's length per unit depth
    }
    if (t < 0.0) discard;
    z = t / len;  // d's forward component is 1 (orthographic: d is forward)
    cosine = dot(normalize(ray.origin + t * ray.direction - draw.sphere.xyz), ray.direction);
  } else if (!materialCovers()) {
    discard;
  }
  passed = filtered ? shadowMapCrossing(fragmentMaterial(), cosine) : vec3(1.0);
  return shadowStoredDepth(l, z);
}
