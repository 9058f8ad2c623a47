// A mesh's material in the viewer's fragment shaders (the scene's and the shadow maps'): its
// textures (set 1), its factors and the sphere it may bound (push constants, MaterialConstants in
// src/gpu/scene_upload.hpp), and the alpha coverage of glTF's MASK and BLEND modes. The
// including shader declares the inputs texCoord0 and texCoord1 first.
#include "ibl/shared/material.h"
#include "ibl/shared/view_bindings.h"

// Base color, emission, sheen color and specular color have sRGB formats: linear here.
layout(set = 1, binding = kMaterialBaseColor) uniform sampler2D baseColorTexture;
layout(set = 1, binding = kMaterialMetallicRoughness) uniform sampler2D metallicRoughnessTexture;
layout(set = 1, binding = kMaterialNormal) uniform sampler2D normalTexture;
layout(set = 1, binding = kMaterialOcclusion) uniform sampler2D occlusionTexture;
layout(set = 1, binding = kMaterialEmissive) uniform sampler2D emissiveTexture;
layout(set = 1, binding = kMaterialSheenColor) uniform sampler2D sheenColorTexture;
layout(set = 1, binding = kMaterialSheenRoughness) uniform sampler2D sheenRoughnessTexture;  // A
layout(set = 1, binding = kMaterialSpecular) uniform sampler2D specularTexture;  // A
layout(set = 1, binding = kMaterialSpecularColor) uniform sampler2D specularColorTexture;
layout(set = 1, binding = kMaterialClearcoat) uniform sampler2D clearcoatTexture;  // R
layout(set = 1, binding = kMaterialClearcoatRoughness) uniform sampler2D clearcoatRoughnessTexture;
layout(set = 1, binding = kMaterialClearcoatNormal) uniform sampler2D clearcoatNormalTexture;
layout(push_constant) uniform Material {
  vec4 baseColorMetallic;
  vec4 emissiveRoughness;
  vec4 scales;       // normal scale, occlusion strength, KHR_materials_ior's ior, the clear
                     // coat's normal scale
  vec4 sphere;       // center, radius: the mesh is a sphere's bounding polyhedron (radius 0: not)
  vec3 alpha;        // baseColorFactor's A, mode (0 opaque, 1 mask, 2 blend), cutoff
  uint clearcoat;    // KHR_materials_clearcoat's factor and roughness, packHalf2x16 (the 128
                     // bytes are full)
  vec4 sheen;        // KHR_materials_sheen: sheenColorFactor, sheenRoughnessFactor
  vec4 specular;     // KHR_materials_specular: specularColorFactor, specularFactor
  uint textureMask;   // 1 base color, 2 metallic-roughness, 4 normal, 8 occlusion, 16 emissive,
                      // 32 sheen color, 64 sheen roughness, 128 specular, 256 specular color,
                      // 512 clear coat, 1024 its roughness, 2048 its normal
  uint texCoordMask;  // the same bits: that texture reads TEXCOORD_1
  int shadowLayer;    // the shadow maps' pass: the layer drawn (view/shadow.vert)
  int scenePass;  // 0 the frame's only scene pass; with screen-space reflections 1 the lit frame
                  // (no area light drawn over the surfaces), 2 the pass that composes them
                  // (kFrameScreenReflection): ScenePass in src/gpu/scene_upload.hpp
} material;

// A uniform number in [0, 1) per pixel and surface depth: BLEND's stochastic threshold (hashed
// alpha; the CPU renderer hashes its rays instead, so the two agree on average, not per pixel).
// (gl_PrimitiveID would need the geometry shader feature.)
float blendThreshold() {
  uvec3 v = uvec3(uvec2(gl_FragCoord.xy), floatBitsToUint(gl_FragCoord.z));
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z;
  return float(v.x >> 8u) * (1.0 / 16777216.0);
}

// The UV set texture slot `bit` reads (glTF texCoord).
vec2 texCoordOf(uint bit) {
  return (material.texCoordMask & bit) != 0u ? texCoord1 : texCoord0;
}

// Whether the material covers this fragment: its alpha (factor times the base color texture's)
// against the mode's rule (alphaCovers in ibl/shared/material.h).
bool materialCovers() {
  float alpha = material.alpha.x;
  if ((material.textureMask & 1u) != 0u) alpha *= texture(baseColorTexture, texCoordOf(1u)).a;
  return alphaCovers(int(material.alpha.y), alpha, material.alpha.z, blendThreshold());
}
