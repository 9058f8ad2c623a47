// The surface a fragment of the viewer's meshes shows, as surfaceAt (src/render/ray_tracer.cpp)
// finds it: spheres ray traced in their bounding polyhedra, the material's textures and normal
// map through ibl/shared/material.h, the side the camera sees. Fragments the material does not
// cover are discarded. Needs view/frame.glsl, the mesh's inputs (view/scene.vert's outputs) and
// view/material.glsl.

// Standard sample locations (Vulkan, "Multisampling"), in pixel units.
vec2 samplePosition(int count, int i) {
  if (count == 2) return i == 0 ? vec2(0.75) : vec2(0.25);
  if (count == 4) {
    const vec2 p4[4] = vec2[4](vec2(0.375, 0.125), vec2(0.875, 0.375), vec2(0.125, 0.625),
                               vec2(0.625, 0.875));
    return p4[i];
  }
  if (count == 8) {
    const vec2 p8[8] = vec2[8](vec2(0.5625, 0.3125), vec2(0.4375, 0.6875), vec2(0.8125, 0.5625),
                               vec2(0.3125, 0.1875), vec2(0.1875, 0.8125), vec2(0.0625, 0.4375),
                               vec2(0.6875, 0.9375), vec2(0.9375, 0.0625));
    return p8[i];
  }
  return vec2(0.5);
}

// A sphere ray traced in its bounding polyhedron, as the CPU renderer intersects it: the samples
// the sphere covers, and the hit point of the pixel's center ray (or of a covered sample's).
// Returns false when the sphere covers none of the pixel's samples. count: the samples per pixel
// at the standard locations (0 or 1: the center alone).
bool traceSphere(int count, out vec3 position, out vec3 normal) {
  Ray center = primaryRay(gl_FragCoord.xy);
  float t = intersectSphere(center, draw.sphere);
  Ray shaded = center;
  if (count > 1) {
    vec2 corner = floor(gl_FragCoord.xy);
    int mask = 0;
    for (int i = 0; i < count; ++i) {
      Ray r = primaryRay(corner + samplePosition(count, i));
      float ti = intersectSphere(r, draw.sphere);
      if (ti < 0.0) continue;
      mask |= 1 << i;
      if (t < 0.0) {
        t = ti;
        shaded = r;
      }
    }
    gl_SampleMask[0] = mask;
  } else {
    gl_SampleMask[0] = -1;
  }
  if (t < 0.0) return false;
  position = shaded.origin + t * shaded.direction;
  normal = normalize(position - draw.sphere.xyz);
  vec4 clip = frame.viewProjection * vec4(position, 1.0);
  gl_FragDepth = clip.z / clip.w;
  return true;
}

struct ShadedSurface {
  vec3 position;     // world
  vec3 normal;       // the shading normal, facing the camera
  vec3 view;         // unit, toward the camera
  SplitSumMaterial material;
  vec4 sheen;        // KHR_materials_sheen: color, roughness
};

// samples: the pass's samples per pixel at the standard locations (0: unknown, the center alone).
ShadedSurface fragmentSurface(int samples) {
  vec3 n = normalize(worldNormal);
  vec3 position = worldPosition;
  if (draw.sphere.w > 0.0) {
    if (!traceSphere(samples, position, n)) discard;
  } else {
    gl_SampleMask[0] = -1;
    gl_FragDepth = gl_FragCoord.z;
  }
  if (!materialCovers()) discard;
  SplitSumMaterial m = fragmentMaterial();
  vec4 sheen = material.sheen;
  sheen.rgb *= slotTexel(sheenColorTexture, kMaterialSheenColor).rgb;
  sheen.w *= slotTexel(sheenRoughnessTexture, kMaterialSheenRoughness).a;
  // The coat's normal: the interpolated one, unless it has a normal map of its own.
  vec3 coatNormal = n;
  if (hasTexture(kMaterialClearcoatNormal))
    coatNormal = applyNormalMap(n, worldTangent,
                                slotTexel(clearcoatNormalTexture, kMaterialClearcoatNormal),
                                material.scales.w);
  if (hasTexture(kMaterialNormal))
    n = applyNormalMap(n, worldTangent, slotTexel(normalTexture, kMaterialNormal),
                       material.scales.x);
  // KHR_materials_anisotropy (surfaceAt's rule): the direction in the frame of the side the mesh
  // faces; the extension's default texel without a texture.
  vec4 anisotropyTexel = hasTexture(kMaterialAnisotropy)
                             ? slotTexel(anisotropyTexture, kMaterialAnisotropy)
                             : vec4(1.0, 0.5, 1.0, 1.0);
  vec3 anisotropy = anisotropyDirectionOf(material.anisotropy.y, anisotropyTexel);
  float anisotropyStrength = clamp(material.anisotropy.x * anisotropy.z, 0.0, 1.0);
  vec3 anisotropyTangent = vec3(1.0, 0.0, 0.0);
  if (anisotropyStrength > 0.0)
    anisotropyTangent = anisotropyTangentOf(
        n, draw.sphere.w > 0.0 ? sphereTangent(n) : worldTangent, anisotropy.xy);
  vec3 ray = frame.cameraPosition.w == 0.0 ? frame.cameraForward.xyz
                                           : normalize(position - frame.cameraPosition.xyz);
  if (dot(n, ray) > 0.0) {  // shade the side the camera sees (the coat's normal alike)
    n = -n;
    coatNormal = -coatNormal;
  }
  // The coat lies over the emission too (KHR_materials_clearcoat, "Emission").
  if (m.clearcoat > 0.0) m.emissive *= 1.0 - clearcoatWeight(m.clearcoat, dot(coatNormal, -ray));
  m.clearcoatNormal = coatNormal;
  m.anisotropy = anisotropyStrength;
  m.anisotropyTangent = anisotropyTangent;
  ShadedSurface surface;
  surface.position = position;
  surface.normal = n;
  surface.view = -ray;
  surface.material = m;
  surface.sheen = sheen;
  return surface;
}
