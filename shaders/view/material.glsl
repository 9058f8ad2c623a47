// A mesh's material in the viewer's fragment shaders (the scene's and the shadow maps'): its
// textures and factors (set 1: MaterialFactors in src/gpu/scene_upload.hpp), the draw's sphere
// and pass (push constants, DrawConstants), and the alpha coverage of glTF's MASK and BLEND
// modes. The including shader declares the inputs texCoord0, texCoord1 and vertexColor first.
#include "ibl/shared/material.h"
#include "ibl/shared/split_sum.h"
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
layout(set = 1, binding = kMaterialIridescence) uniform sampler2D iridescenceTexture;  // R
layout(set = 1, binding = kMaterialIridescenceThickness) uniform sampler2D
    iridescenceThicknessTexture;  // G
layout(set = 1, binding = kMaterialAnisotropy) uniform sampler2D anisotropyTexture;  // RGB
layout(set = 1, binding = kMaterialTransmission) uniform sampler2D transmissionTexture;  // R
layout(set = 1, binding = kMaterialThickness) uniform sampler2D thicknessTexture;        // G
layout(std430, set = 1, binding = kMaterialFactors) readonly buffer Material {
  vec4 baseColorMetallic;
  vec4 emissiveRoughness;
  vec4 scales;     // normal scale, occlusion strength, KHR_materials_ior's ior, the clear coat's
                   // normal scale
  vec4 alpha;      // baseColorFactor's A, mode (0 opaque, 1 mask, 2 blend), cutoff, 1 if unlit
  vec4 clearcoat;  // KHR_materials_clearcoat's factor and roughness
  vec4 sheen;      // KHR_materials_sheen: sheenColorFactor, sheenRoughnessFactor
  vec4 specular;   // KHR_materials_specular: specularColorFactor, specularFactor
  vec4 iridescence;  // KHR_materials_iridescence: factor, IOR, thickness minimum and maximum (nm)
  vec4 anisotropy;   // KHR_materials_anisotropy: strength, rotation (radians), 0, 0
  // KHR_materials_transmission and _volume: transmission, thickness, attenuation distance, 0;
  // the attenuation color, 0
  vec4 transmission;
  vec4 attenuation;
  uint texCoordMask;  // bit b: the texture at binding b reads TEXCOORD_1
  // KHR_texture_transform: binding b's UvTransform rows u and v at 2b and 2b + 1.
  vec4 uvTransforms[2 * 17];
} material;
layout(push_constant) uniform Draw {
  vec4 sphere;     // center, radius: the mesh is a sphere's bounding polyhedron (radius 0: not)
  int shadowLayer;  // the shadow maps' pass: the layer drawn (view/shadow.vert)
  int scenePass;  // 0 the frame's only scene pass; with screen-space reflections 1 the lit frame
                  // (no area light drawn over the surfaces), 2 the pass that composes them
                  // (kFrameScreenReflection); 3 the opaque frame behind transmissive
                  // surfaces (kFrameTransmissionFrame); 4 and 5 the shadow maps' depths and
                  // filters (view/shadow.glsl): ScenePass in src/gpu/scene_upload.hpp
  // bit b: the texture at binding b is the material's (else white). Here, not with the factors:
  // it decides where derivatives are taken (slotTexel), which needs a uniform condition that the
  // helper invocations read too.
  uint textureMask;
  float thicknessScale;  // KHR_materials_volume: the node's scale of the thickness (Mesh)
} draw;

// Whether the material has a texture at `binding` (MaterialBinding).
bool hasTexture(int binding) {
  return (draw.textureMask & (1u << uint(binding))) != 0u;
}

// The texel of `t`, the texture at `binding`, for this fragment: at its UV set's coordinates
// (glTF texCoord) through its KHR_texture_transform; white (which multiplies nothing) where the
// material has none. The screen derivatives are the UV set's, carried through the map's linear
// part and passed explicitly: an implicit one would difference the map across the pixel quad, and
// lavapipe reads a storage buffer as zeros in the quad's helper invocations.
struct SlotLookup {
  vec2 uv;      // transformed
  vec2 dx, dy;  // the uv's change one pixel over in x and in y
};
// fine: the derivatives within the pixel's own row and column of the quad (dFdxFine), as the
// specular antialiasing's partner pixel needs them; else the driver's choice (texture filtering).
SlotLookup slotLookup(int binding, bool fine) {
  vec2 dx0 = fine ? dFdxFine(texCoord0) : dFdx(texCoord0);
  vec2 dy0 = fine ? dFdyFine(texCoord0) : dFdy(texCoord0);
  vec2 dx1 = fine ? dFdxFine(texCoord1) : dFdx(texCoord1);
  vec2 dy1 = fine ? dFdyFine(texCoord1) : dFdy(texCoord1);
  bool second = (material.texCoordMask & (1u << uint(binding))) != 0u;
  UvTransform m;
  m.u = material.uvTransforms[2 * binding].xyz;
  m.v = material.uvTransforms[2 * binding + 1].xyz;
  mat2 linear = mat2(m.u.x, m.v.x, m.u.y, m.v.y);  // columns: d(uv')/du, d(uv')/dv
  SlotLookup l;
  l.uv = transformUv(m, second ? texCoord1 : texCoord0);
  l.dx = linear * (second ? dx1 : dx0);
  l.dy = linear * (second ? dy1 : dy0);
  return l;
}
vec4 slotTexel(sampler2D t, int binding) {
  if (!hasTexture(binding)) return vec4(1.0);
  SlotLookup l = slotLookup(binding, false);
  return textureGrad(t, l.uv, l.dx, l.dy);
}

// How much metallic changes from this pixel to the next in x or in y (the larger): its texture
// read one pixel over, in this invocation (the quad's helpers read the factors as zeros on
// lavapipe, so no derivative of the factors is taken); 0 without a texture.
float metallicChangeAcrossPixel() {
  if (!hasTexture(kMaterialMetallicRoughness)) return 0.0;
  SlotLookup l = slotLookup(kMaterialMetallicRoughness, false);
  float here = textureGrad(metallicRoughnessTexture, l.uv, l.dx, l.dy).b;
  float x = textureGrad(metallicRoughnessTexture, l.uv + l.dx, l.dx, l.dy).b;
  float y = textureGrad(metallicRoughnessTexture, l.uv + l.dy, l.dx, l.dy).b;
  return material.baseColorMetallic.a * max(abs(x - here), abs(y - here));
}

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

// Whether the material covers this fragment: its alpha (factor times the base color texture's
// times the vertex color's) against the mode's rule (alphaCovers in ibl/shared/material.h).
bool materialCovers() {
  float alpha =
      material.alpha.x * slotTexel(baseColorTexture, kMaterialBaseColor).a * vertexColor.a;
  return alphaCovers(int(material.alpha.y), alpha, material.alpha.z, blendThreshold());
}

// The material at this fragment with its textures applied, as surfaceAt reads it: everything
// but what takes the surface's frame (the coat's normal, the anisotropy's direction, which
// view/surface.glsl adds) and the coat's share of the emission. Needs the fragment covered.
SplitSumMaterial fragmentMaterial() {
  SplitSumMaterial m;
  // sRGB textures are decoded before filtering (their formats), as Texture::sample does.
  m.baseColor = material.baseColorMetallic.rgb *
                slotTexel(baseColorTexture, kMaterialBaseColor).rgb * vertexColor.rgb;
  vec2 mr = applyMetallicRoughnessTexel(
      material.baseColorMetallic.a, material.emissiveRoughness.a,
      slotTexel(metallicRoughnessTexture, kMaterialMetallicRoughness));
  m.metallic = clamp(mr.x, 0.0, 1.0);
  m.roughness = clamp(mr.y, 0.0, 1.0);
  m.occlusion =
      occlusionFromTexel(material.scales.y, slotTexel(occlusionTexture, kMaterialOcclusion));
  m.emissive =
      material.emissiveRoughness.rgb * slotTexel(emissiveTexture, kMaterialEmissive).rgb;
  if (material.alpha.w != 0.0) m.emissive *= vertexColor.rgb;  // unlit: the base color's place
  m.ior = material.scales.z;
  m.specular = material.specular.w * slotTexel(specularTexture, kMaterialSpecular).a;
  m.specularColor =
      material.specular.rgb * slotTexel(specularColorTexture, kMaterialSpecularColor).rgb;
  // KHR_materials_clearcoat: factor, roughness.
  vec2 coat = material.clearcoat.xy;
  coat.x *= slotTexel(clearcoatTexture, kMaterialClearcoat).r;
  coat.y *= slotTexel(clearcoatRoughnessTexture, kMaterialClearcoatRoughness).g;
  coat = clamp(coat, 0.0, 1.0);
  m.clearcoat = coat.x;
  m.clearcoatRoughness = coat.y;
  m.clearcoatNormal = vec3(0.0, 0.0, 1.0);
  // KHR_materials_iridescence: factor, IOR, thicknesses.
  vec4 iridescence = material.iridescence;
  m.iridescence =
      clamp(iridescence.x * slotTexel(iridescenceTexture, kMaterialIridescence).r, 0.0, 1.0);
  m.iridescenceIor = iridescence.y;
  m.iridescenceThickness =
      mix(iridescence.z, iridescence.w,
          slotTexel(iridescenceThicknessTexture, kMaterialIridescenceThickness).g);
  m.anisotropy = 0.0;
  m.anisotropyTangent = vec3(1.0, 0.0, 0.0);
  // KHR_materials_transmission and _volume: the share transmitted, the thickness, and the
  // volume's attenuation (a thin wall's none).
  m.transmission =
      clamp(material.transmission.x * slotTexel(transmissionTexture, kMaterialTransmission).r,
            0.0, 1.0);
  bool volume = material.transmission.y > 0.0 && material.scales.z > 0.0;  // ior 0: a thin wall
  m.thickness = volume ? material.transmission.y * draw.thicknessScale *
                             slotTexel(thicknessTexture, kMaterialThickness).g
                       : 0.0;
  m.attenuation = volume ? volumeAttenuationCoefficient(material.attenuation.rgb,
                                                        material.transmission.z)
                         : vec3(0.0);
  if (frame.bufferView.y != 0) {
    // Clay: a matte gray dielectric (the emission but an unlit material's, the occlusion and, in
    // fragmentSurface, the normal map and the coverage kept).
    m.baseColor = vec3(0.5);
    m.metallic = 0.0;
    m.roughness = 0.6;
    m.ior = 1.5;
    m.specular = 1.0;
    m.specularColor = vec3(1.0);
    m.clearcoat = 0.0;
    m.iridescence = 0.0;
    m.transmission = 0.0;
    m.thickness = 0.0;
    m.attenuation = vec3(0.0);
    // An unlit material's color is its emission (KHR_materials_unlit): clay like the rest.
    if (material.alpha.w != 0.0) m.emissive = vec3(0.0);
  }
  return m;
}
