// The surface a fragment of the viewer's meshes shows, as surfaceAt (src/render/ray_tracer.cpp)
// finds it: spheres ray traced in their bounding polyhedra, the material's textures and normal
// map through ibl/shared/material.h, the side the camera sees. Fragments the material does not
// cover are discarded. Needs view/frame.glsl, the mesh's inputs (view/scene.vert's outputs) and
// view/material.glsl.

#include "ibl/shared/buffer_views.h"
#include "ibl/shared/specular_antialiasing.h"

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
// Returns false when the sphere covers none of the pixel's samples (position and normal are then
// the sphere's point nearest the center ray). count: the samples per pixel at the standard
// locations (0 or 1: the center alone).
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
  // Where the sphere is missed, the point nearest the ray: a normal for the quad's derivatives.
  float along = t < 0.0 ? -dot(shaded.origin - draw.sphere.xyz, shaded.direction) : t;
  position = shaded.origin + along * shaded.direction;
  normal = normalize(position - draw.sphere.xyz);
  vec4 clip = frame.viewProjection * vec4(position, 1.0);
  gl_FragDepth = clip.z / clip.w;
  return t >= 0.0;
}

struct ShadedSurface {
  vec3 position;     // world
  vec3 normal;       // the shading normal, facing the camera
  vec3 view;         // unit, toward the camera
  SplitSumMaterial material;
  vec4 sheen;        // KHR_materials_sheen: color, roughness
  float metallicChange;  // for the validation view: metallicChangeAcrossPixel (else 0)
};

// Specular antialiasing's other pixel, as the CPU's antialiasSpecular takes it: the partner in
// the 2 x 2 quad, right of an even column and left of an odd one, below an even row and above an
// odd one.
float quadPartnerStep(float coordinate) {
  return (int(floor(coordinate)) & 1) == 0 ? 1.0 : -1.0;
}

// The shading normal at the quad partner's pixel along x (alongX) or y, from this invocation's
// own inputs carried one pixel over by their screen derivatives, or on a traced sphere from the
// partner's ray (the sphere's nearest point where it misses). The normal map `t` at `binding`,
// when the material has one, is read at the partner's texture coordinates, scaled by `scale`.
// (Not the partner's own values through dFdx: a helper invocation reads the material's factors
// as zeros on lavapipe.) Needs uniform control flow.
vec3 partnerNormal(bool alongX, sampler2D t, int binding, float scale) {
  float s = quadPartnerStep(alongX ? gl_FragCoord.x : gl_FragCoord.y);
  if (draw.sphere.w > 0.0) {
    Ray r = primaryRay(gl_FragCoord.xy + (alongX ? vec2(s, 0.0) : vec2(0.0, s)));
    float hit = intersectSphere(r, draw.sphere);
    float along = hit < 0.0 ? -dot(r.origin - draw.sphere.xyz, r.direction) : hit;
    return normalize(r.origin + along * r.direction - draw.sphere.xyz);
  }
  vec3 n = normalize(worldNormal + s * (alongX ? dFdxFine(worldNormal) : dFdyFine(worldNormal)));
  if (!hasTexture(binding)) return n;
  vec4 tangent = worldTangent + s * (alongX ? dFdxFine(worldTangent) : dFdyFine(worldTangent));
  SlotLookup l = slotLookup(binding, true);
  vec4 texel = textureGrad(t, l.uv + s * (alongX ? l.dx : l.dy), l.dx, l.dy);
  return applyNormalMap(n, tangent, texel, scale);
}

// samples: the pass's samples per pixel at the standard locations (0: unknown, the center alone).
// specularAntialiasing: widen the lobes by the normals' change to the quad partner's pixel
// (ibl/shared/specular_antialiasing.h; uniform over the draw). A fragment the surface does not
// cover is discarded only after every screen derivative is taken.
ShadedSurface fragmentSurface(int samples, bool specularAntialiasing) {
  vec3 n = normalize(worldNormal);
  vec3 position = worldPosition;
  bool covered = true;
  if (draw.sphere.w > 0.0) {
    covered = traceSphere(samples, position, n);
  } else {
    gl_SampleMask[0] = -1;
    gl_FragDepth = gl_FragCoord.z;
  }
  covered = materialCovers() && covered;
  SplitSumMaterial m = fragmentMaterial();
  vec4 sheen = material.sheen;
  sheen.rgb *= slotTexel(sheenColorTexture, kMaterialSheenColor).rgb;
  sheen.w *= slotTexel(sheenRoughnessTexture, kMaterialSheenRoughness).a;
  if (frame.bufferView.y != 0) sheen = vec4(0.0);  // clay
  // The coat's normal: the interpolated one, unless it has a normal map of its own.
  // With each map, the spread of normals its filtered texel averaged (specular antialiasing).
  vec3 coatNormal = n;
  float coatMapAlpha2 = 0.0, mapAlpha2 = 0.0;
  if (hasTexture(kMaterialClearcoatNormal)) {
    vec4 texel = slotTexel(clearcoatNormalTexture, kMaterialClearcoatNormal);
    coatNormal = applyNormalMap(n, worldTangent, texel, material.scales.w);
    coatMapAlpha2 = normalMapAlpha2(texel.xyz, material.scales.w);
  }
  if (hasTexture(kMaterialNormal)) {
    vec4 texel = slotTexel(normalTexture, kMaterialNormal);
    n = applyNormalMap(n, worldTangent, texel, material.scales.x);
    mapAlpha2 = normalMapAlpha2(texel.xyz, material.scales.x);
  }
  // KHR_materials_anisotropy (surfaceAt's rule): the direction in the frame of the side the mesh
  // faces; the extension's default texel without a texture.
  vec4 anisotropyTexel = hasTexture(kMaterialAnisotropy)
                             ? slotTexel(anisotropyTexture, kMaterialAnisotropy)
                             : vec4(1.0, 0.5, 1.0, 1.0);
  vec3 anisotropy = anisotropyDirectionOf(material.anisotropy.y, anisotropyTexel);
  float anisotropyStrength = clamp(material.anisotropy.x * anisotropy.z, 0.0, 1.0);
  if (frame.bufferView.y != 0) anisotropyStrength = 0.0;  // clay
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
  if (specularAntialiasing) {
    // The partners' normals on this fragment's side (antialiasSpecular's rule on the CPU).
    vec3 nx = partnerNormal(true, normalTexture, kMaterialNormal, material.scales.x);
    vec3 ny = partnerNormal(false, normalTexture, kMaterialNormal, material.scales.x);
    nx = dot(nx, n) < 0.0 ? -nx : nx;
    ny = dot(ny, n) < 0.0 ? -ny : ny;
    m.roughness = specularAntialiasedRoughness(m.roughness, mapAlpha2, nx - n, ny - n);
    vec3 cx = partnerNormal(true, clearcoatNormalTexture, kMaterialClearcoatNormal,
                            material.scales.w);
    vec3 cy = partnerNormal(false, clearcoatNormalTexture, kMaterialClearcoatNormal,
                            material.scales.w);
    cx = dot(cx, coatNormal) < 0.0 ? -cx : cx;
    cy = dot(cy, coatNormal) < 0.0 ? -cy : cy;
    m.clearcoatRoughness = specularAntialiasedRoughness(m.clearcoatRoughness, coatMapAlpha2,
                                                        cx - coatNormal, cy - coatNormal);
  }
  float metallicChange =
      frame.bufferView.x == kBufferValidation ? metallicChangeAcrossPixel() : 0.0;
  if (!covered) discard;
  m.anisotropy = anisotropyStrength;
  m.anisotropyTangent = anisotropyTangent;
  ShadedSurface surface;
  surface.position = position;
  surface.normal = n;
  surface.view = -ray;
  surface.material = m;
  surface.sheen = sheen;
  surface.metallicChange = metallicChange;
  return surface;
}
