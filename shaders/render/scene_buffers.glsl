// The scene as the device's ray tracers read it (uploadSceneBuffers in src/gpu/scene_buffers.cpp):
// the triangles' BVH, the meshes, materials, textures, lights and spheres in storage buffers, and
// what is built on them: textures, surfaces at a hit (surfaceAt in src/render/ray_tracer.cpp) and
// rays against the scene. The reference (render/path_trace.comp) binds them in set 0, the irradiance
// volume's update (view/volume_trace.comp) in set 1: define SCENE_SET before including.
#ifndef SCENE_SET
#define SCENE_SET 0
#endif
layout(std430, set = SCENE_SET, binding = 0) readonly buffer Parameters {
  vec4 cameraPosition;  // w: 1 perspective, 0 orthographic
  vec4 cameraForward;
  vec4 cameraRight;  // scaled to the image's half width (perspective: at distance 1)
  vec4 cameraUp;     // scaled to its half height
  vec4 background;   // rgb: the background without the environment
  uvec4 image;       // width, height, first sample index, samples
  uvec4 counts;      // lights, spheres, emitters, the environment's cube size
  uvec4 offsets;     // in sceneData: vertices, materials, textures, lights
  uvec4 offsets2;    // in sceneData: spheres, emitters; in words: texels, emitter entries
  ivec4 shading;     // PathShading: diffuse, multiple scattering, micro-occlusion, sheen
  ivec4 path;        // bounces, lobes, flags (kFlag...), seed
} params;
// The BVH (src/gpu/bvh.hpp): nodes, then triangles.
layout(std430, set = SCENE_SET, binding = 1) readonly buffer Nodes {
  vec4 nodes[];
};
layout(std430, set = SCENE_SET, binding = 2) readonly buffer Triangles {
  vec4 bvhTriangles[];
};
// Meshes (one vec4 of uint bits each: first vertex, first index, material, flags), vertices
// (three each), materials (kMaterialRecordVec4s), textures (one), lights (five), spheres (two), emitters (one):
// uploadSceneBuffers in src/gpu/scene_buffers.cpp.
layout(std430, set = SCENE_SET, binding = 3) readonly buffer SceneData {
  vec4 sceneData[];
};
// The meshes' indices, then the textures' texels (RGBA8), then per emissive mesh and primitive
// its emitter's entry (or ~0).
layout(std430, set = SCENE_SET, binding = 4) readonly buffer Words {
  uint words[];
};

#include "ibl/shared/lang.h"
#include "ibl/shared/color.h"
#include "ibl/shared/light_record.h"
#include "ibl/shared/material.h"
#include "ibl/shared/transmission.h"
#include "ibl/shared/view_bindings.h"
#include "ibl/shared/bvh.h"

uint bitsAt(vec4 v, int c) {
  return floatBitsToUint(v[c]);
}

// --- Textures (Texture::sample in src/render/scene.cpp) ---

vec4 texelAt(uvec4 t, int x, int y, bool srgb) {
  int w = int(t.y), h = int(t.z);
  int wx = wrapTexel(x, w, int(t.w & 3u)), wy = wrapTexel(y, h, int((t.w >> 2u) & 3u));
  uint packed = words[params.offsets2.z + t.x + uint(wy * w + wx)];
  vec4 c = vec4(float(packed & 255u), float((packed >> 8u) & 255u), float((packed >> 16u) & 255u),
                float(packed >> 24u)) / 255.0;
  if (srgb) c.rgb = srgbToLinear(c.rgb);
  return c;
}

vec4 sampleTexture(int index, vec2 uv, bool srgb) {
  vec4 r = sceneData[params.offsets.z + uint(index)];
  uvec4 t = uvec4(bitsAt(r, 0), bitsAt(r, 1), bitsAt(r, 2), bitsAt(r, 3));
  float fx = uv.x * float(t.y), fy = uv.y * float(t.z);
  if ((t.w & 16u) != 0u) return texelAt(t, int(floor(fx)), int(floor(fy)), srgb);
  float flx = floor(fx - 0.5), fly = floor(fy - 0.5);
  float wx = fx - 0.5 - flx, wy = fy - 0.5 - fly;
  int x0 = int(flx), y0 = int(fly);
  return (texelAt(t, x0, y0, srgb) * (1.0 - wx) + texelAt(t, x0 + 1, y0, srgb) * wx) * (1.0 - wy) +
         (texelAt(t, x0, y0 + 1, srgb) * (1.0 - wx) + texelAt(t, x0 + 1, y0 + 1, srgb) * wx) * wy;
}

// --- Meshes and materials ---

struct MeshRecord {
  uint firstVertex, firstIndex, material, flags;  // flags: 1 tangents, 2 uv0, 4 uv1, 8 emitters
};
MeshRecord meshAt(uint mesh) {
  vec4 r = sceneData[mesh];
  return MeshRecord(bitsAt(r, 0), bitsAt(r, 1), bitsAt(r, 2), bitsAt(r, 3));
}
uvec3 triangleVertices(MeshRecord m, uint primitive) {
  uint i = m.firstIndex + 3u * primitive;
  return m.firstVertex + uvec3(words[i], words[i + 1u], words[i + 2u]);
}
// Entry k of vertex v's record (kVertexRecordVec4s in ibl/shared/material.h).
vec4 vertexAt(uint v, int k) {
  return sceneData[params.offsets.x + uint(kVertexRecordVec4s) * v + uint(k)];
}
// The vertex color (COLOR_0) at barycentrics w of a triangle.
vec4 vertexColorAt(uvec3 tri, vec3 w) {
  return vertexAt(tri.x, 4) * w.x + vertexAt(tri.y, 4) * w.y + vertexAt(tri.z, 4) * w.z;
}
vec4 materialAt(uint material, int k) {
  return sceneData[params.offsets.y + uint(kMaterialRecordVec4s) * material + uint(k)];
}
// Texture slot `binding` (MaterialBinding) of a material: (texture index, texCoord) or texture -1.
ivec2 materialSlot(uint material, int binding) {
  int e = int(materialAt(material, kMaterialRecordSlots + binding / 4)[binding % 4]);
  return e < 0 ? ivec2(-1, 0) : ivec2(e >> 1, e & 1);
}
// The UV at which slot `binding` of the material reads barycentrics (w0, u, v) of a triangle:
// its UV set's, through its KHR_texture_transform; false when the mesh lacks that set.
bool slotUv(MeshRecord m, uvec3 tri, uint material, int binding, vec3 w, out vec2 uv) {
  uv = vec2(0.0);
  ivec2 slot = materialSlot(material, binding);
  if (slot.x < 0) return false;
  if (slot.y == 0 && (m.flags & 2u) == 0u) return false;
  if (slot.y == 1 && (m.flags & 4u) == 0u) return false;
  for (int k = 0; k < 3; ++k)
    uv += w[k] * (slot.y == 0 ? vec2(vertexAt(tri[k], 0).w, vertexAt(tri[k], 1).w)
                              : vertexAt(tri[k], 3).xy);
  UvTransform t;
  t.u = materialAt(material, kMaterialRecordUvTransforms + 2 * binding).xyz;
  t.v = materialAt(material, kMaterialRecordUvTransforms + 2 * binding + 1).xyz;
  uv = transformUv(t, uv);
  return true;
}

// The texel of slot `binding` at barycentrics w, sRGB-decoded if asked; white (which
// multiplies nothing) when the material has no texture there or the mesh lacks its UV set, as
// Texture::sample gives for none.
vec4 slotTexel(MeshRecord m, uvec3 tri, uint material, int binding, vec3 w, bool srgb) {
  vec2 uv;
  return slotUv(m, tri, material, binding, w, uv)
             ? sampleTexture(materialSlot(material, binding).x, uv, srgb)
             : vec4(1.0);
}

bool bvhCovers(int triangle, float u, float v, vec3 origin, vec3 dir) {
  uint mesh = floatBitsToUint(bvhTriangles[3 * triangle].w);
  uint primitive = floatBitsToUint(bvhTriangles[3 * triangle + 1].w);
  MeshRecord m = meshAt(mesh);
  vec4 m3 = materialAt(m.material, 3);
  int mode = int(m3.z);
  if (mode == 0) return true;
  uvec3 tri = triangleVertices(m, primitive);
  vec3 w = vec3(1.0 - u - v, u, v);
  float alpha = materialAt(m.material, 0).w *
                slotTexel(m, tri, m.material, kMaterialBaseColor, w, false).a *
                vertexColorAt(tri, w).a;
  return alphaCovers(mode, alpha, m3.w, rayBlendThreshold(origin, dir, primitive));
}
vec4 bvhNodeAt(int i) {
  return nodes[i];
}
vec4 bvhTriangleAt(int i) {
  return bvhTriangles[i];
}

// --- The scene's surfaces (RayTracer and surfaceAt in src/render/ray_tracer.cpp) ---

struct SceneHit {
  bool found;
  float t;
  bool sphere;
  uint mesh;       // or the sphere
  uint primitive;
  float u, v;
};

SceneHit intersectScene(vec3 origin, vec3 dir, float tMax, bool anyHit) {
  SceneHit h = SceneHit(false, tMax, false, 0u, 0u, 0.0, 0.0);
  BvhHit b = bvhIntersect(origin, dir, tMax, anyHit);
  if (b.found) {
    h = SceneHit(true, b.t, false, floatBitsToUint(bvhTriangles[3 * b.triangle].w),
                 floatBitsToUint(bvhTriangles[3 * b.triangle + 1].w), b.u, b.v);
    if (anyHit) return h;
  }
  for (uint s = 0u; s < params.counts.y; ++s) {
    vec4 sphere = sceneData[params.offsets2.x + 2u * s];
    float t = raySphereDistance(origin, dir, sphere.xyz, sphere.w);
    if (t > 0.0 && t < h.t) {
      h = SceneHit(true, t, true, s, 0u, 0.0, 0.0);
      if (anyHit) return h;
    }
  }
  return h;
}

bool occluded(vec3 origin, vec3 dir, float maxDistance) {
  return intersectScene(origin, dir, maxDistance, true).found;
}

struct Surface {
  vec3 position, normal;
  vec3 baseColor;
  float metallic, roughness;
  vec3 emissive;
  vec3 sheenColor;
  float sheenRoughness;
  float ior, specular;  // KHR_materials_ior and _specular (texture applied)
  vec3 specularColor;
  // KHR_materials_clearcoat (textures applied; 0: none), the coat's normal on the normal's side;
  // the emission above is what the coat lets through toward the ray's origin.
  float clearcoat, clearcoatRoughness;
  vec3 clearcoatNormal;
  // KHR_materials_iridescence (textures applied; 0: none): strength, the film's IOR and thickness.
  float iridescence, iridescenceIor, iridescenceThickness;
  // KHR_materials_anisotropy (texture applied; 0: none): strength, the direction of the larger
  // roughness (unit, orthogonal to the normal).
  float anisotropy;
  vec3 anisotropyTangent;
  // KHR_materials_transmission and _volume (textures applied; transmission 0: none): whether the
  // mesh bounds a volume, its thickness, its attenuation coefficient, and whether the ray met
  // the side the normals face (SurfacePoint's).
  float transmission;
  bool volume;
  float thickness;
  vec3 attenuation;
  vec3 faceNormal;
  bool frontFace;
};

Surface surfaceAt(SceneHit hit, vec3 origin, vec3 dir) {
  Surface p;
  p.position = origin + hit.t * dir;
  vec3 n, coatNormal;
  uint material;
  vec4 m5;
  // KHR_materials_anisotropy: the tangent frame, and the texel (the extension's default without
  // a texture).
  vec4 tangent = vec4(0.0), anisotropyTexel = vec4(1.0, 0.5, 1.0, 1.0);
  if (hit.sphere) {
    vec4 sphere = sceneData[params.offsets2.x + 2u * hit.mesh];
    n = normalize(p.position - sphere.xyz);
    material = floatBitsToUint(sceneData[params.offsets2.x + 2u * hit.mesh + 1u].x);
    tangent = sphereTangent(n);
  } else {
    MeshRecord m = meshAt(hit.mesh);
    material = m.material;
    uvec3 tri = triangleVertices(m, hit.primitive);
    vec3 w = vec3(1.0 - hit.u - hit.v, hit.u, hit.v);
    n = normalize(vertexAt(tri.x, 1).xyz * w.x + vertexAt(tri.y, 1).xyz * w.y +
                  vertexAt(tri.z, 1).xyz * w.z);
    // The side the ray meets: the triangle's plane, turned to its normals' side (surfaceAt's).
    vec3 a = vertexAt(tri.x, 0).xyz;
    vec3 face = cross(vertexAt(tri.y, 0).xyz - a, vertexAt(tri.z, 0).xyz - a);
    if (dot(face, vertexAt(tri.x, 1).xyz + vertexAt(tri.y, 1).xyz + vertexAt(tri.z, 1).xyz) < 0.0)
      face = -face;
    float area2 = dot(face, face);
    p.faceNormal = area2 > 0.0 ? face / sqrt(area2) : n;
    p.frontFace = dot(p.faceNormal, dir) <= 0.0;
    vec4 m0 = materialAt(material, 0), m1 = materialAt(material, 1), m2 = materialAt(material, 2),
         m3 = materialAt(material, 3), m4 = materialAt(material, 4);
    m5 = materialAt(material, 5);
    vec3 base = m0.rgb * slotTexel(m, tri, material, kMaterialBaseColor, w, true).rgb *
                vertexColorAt(tri, w).rgb;
    vec2 mr = applyMetallicRoughnessTexel(
        m1.w, m3.x, slotTexel(m, tri, material, kMaterialMetallicRoughness, w, false));
    float metallic = mr.x, roughness = mr.y;
    vec3 emissive = m1.rgb * slotTexel(m, tri, material, kMaterialEmissive, w, true).rgb;
    // Unlit (m7.x = 1): the emission is the base color's, so the vertex colors multiply it.
    if (materialAt(material, 7).x != 0.0) emissive *= vertexColorAt(tri, w).rgb;
    p.sheenColor = m2.rgb * slotTexel(m, tri, material, kMaterialSheenColor, w, true).rgb;
    p.sheenRoughness =
        clamp(m2.w * slotTexel(m, tri, material, kMaterialSheenRoughness, w, false).a, 0.0, 1.0);
    p.specularColor = m4.rgb * slotTexel(m, tri, material, kMaterialSpecularColor, w, true).rgb;
    p.specular = m4.w * slotTexel(m, tri, material, kMaterialSpecular, w, false).a;
    p.clearcoat =
        clamp(m5.y * slotTexel(m, tri, material, kMaterialClearcoat, w, false).r, 0.0, 1.0);
    p.clearcoatRoughness = clamp(
        m5.z * slotTexel(m, tri, material, kMaterialClearcoatRoughness, w, false).g, 0.0, 1.0);
    vec4 m6 = materialAt(material, 6);
    p.iridescence =
        clamp(m6.x * slotTexel(m, tri, material, kMaterialIridescence, w, false).r, 0.0, 1.0);
    // No thickness texture: white, so the maximum.
    p.iridescenceThickness =
        mix(m6.z, m6.w, slotTexel(m, tri, material, kMaterialIridescenceThickness, w, false).g);
    vec4 m8 = materialAt(material, 8);
    p.transmission =
        clamp(m8.x * slotTexel(m, tri, material, kMaterialTransmission, w, false).r, 0.0, 1.0);
    p.thickness = m8.y * slotTexel(m, tri, material, kMaterialThickness, w, false).g;
    // The coat's normal: the interpolated one, unless it has a normal map of its own.
    coatNormal = n;
    vec2 uv;
    if ((m.flags & 1u) != 0u) {
      tangent = vertexAt(tri.x, 2) * w.x + vertexAt(tri.y, 2) * w.y + vertexAt(tri.z, 2) * w.z;
      if (slotUv(m, tri, material, kMaterialClearcoatNormal, w, uv))
        coatNormal = applyNormalMap(
            n, tangent,
            sampleTexture(materialSlot(material, kMaterialClearcoatNormal).x, uv, false), m5.w);
      if (slotUv(m, tri, material, kMaterialNormal, w, uv))
        n = applyNormalMap(
            n, tangent, sampleTexture(materialSlot(material, kMaterialNormal).x, uv, false), m3.y);
    }
    if (slotUv(m, tri, material, kMaterialAnisotropy, w, uv))
      anisotropyTexel = sampleTexture(materialSlot(material, kMaterialAnisotropy).x, uv, false);
    p.baseColor = base;
    p.metallic = clamp(metallic, 0.0, 1.0);
    p.roughness = clamp(roughness, 0.0, 1.0);
    p.emissive = emissive;
  }
  if (hit.sphere) {
    vec4 m0 = materialAt(material, 0), m1 = materialAt(material, 1), m2 = materialAt(material, 2);
    p.baseColor = m0.rgb;
    p.metallic = m1.w;
    p.roughness = materialAt(material, 3).x;
    p.emissive = m1.rgb;
    p.sheenColor = m2.rgb;
    p.sheenRoughness = m2.w;
    p.specularColor = materialAt(material, 4).rgb;
    p.specular = materialAt(material, 4).w;
    m5 = materialAt(material, 5);
    p.clearcoat = m5.y;
    p.clearcoatRoughness = m5.z;
    p.iridescence = materialAt(material, 6).x;
    p.iridescenceThickness = materialAt(material, 6).w;
    p.transmission = materialAt(material, 8).x;
    p.thickness = materialAt(material, 8).y;
    p.faceNormal = n;
    p.frontFace = dot(n, dir) <= 0.0;
    coatNormal = n;
  }
  vec4 m8 = materialAt(material, 8);
  p.volume = m8.y > 0.0 && m5.x > 0.0;  // an infinite index: a thin wall (surfaceAt's rule)
  p.attenuation =
      p.volume ? volumeAttenuationCoefficient(materialAt(material, 9).rgb, m8.z) : vec3(0.0);
  p.ior = m5.x;
  p.iridescenceIor = materialAt(material, 6).y;
  // The anisotropy's direction in the frame of the side the mesh faces (surfaceAt's rule).
  vec4 m7 = materialAt(material, 7);
  vec3 anisotropy = anisotropyDirectionOf(m7.z, anisotropyTexel);
  p.anisotropy = clamp(m7.y * anisotropy.z, 0.0, 1.0);
  p.anisotropyTangent = vec3(1.0, 0.0, 0.0);
  if (p.anisotropy > 0.0) p.anisotropyTangent = anisotropyTangentOf(n, tangent, anisotropy.xy);
  // Shade the side the ray sees (the coat's normal on the same side).
  if (dot(n, dir) > 0.0) {
    n = -n;
    coatNormal = -coatNormal;
  }
  p.normal = n;
  p.clearcoatNormal = coatNormal;
  // The coat lies over the emission too (KHR_materials_clearcoat, "Emission").
  if (p.clearcoat > 0.0) p.emissive *= 1.0 - clearcoatWeight(p.clearcoat, dot(coatNormal, -dir));
  return p;
}

// The Fresnel reflectance of the surface's material (specularReflectance and withIridescence,
// ibl/shared/material.h).
SpecularReflectance surfaceReflectance(Surface p, bool microOcclusion) {
  return withIridescence(specularReflectance(p.baseColor, p.metallic, p.ior, p.specular,
                                             p.specularColor, microOcclusion),
                         p.iridescence, p.iridescenceIor, p.iridescenceThickness);
}

// A probe capture's view of a metal (RenderOptions::captureMetalsAsDiffuse): a diffuse surface
// of its F0.
Surface metalAsDiffuse(Surface p) {
  p.baseColor = metalAsDiffuseColor(p.baseColor, p.metallic, surfaceReflectance(p, false).f0);
  p.specular *= 1.0 - p.metallic;  // fresnel_mix's layer: the dielectric share's alone
  p.metallic = 0.0;
  return p;
}

// The material of the surface a hit met.
uint hitMaterialIndex(SceneHit hit) {
  return hit.sphere ? floatBitsToUint(sceneData[params.offsets2.x + 2u * hit.mesh + 1u].x)
                    : meshAt(hit.mesh).material;
}
// Whether it may transmit (KHR_materials_transmission's factor; its texture may still say not).
bool materialTransmits(SceneHit hit) {
  return materialAt(hitMaterialIndex(hit), 8).x > 0.0;
}
