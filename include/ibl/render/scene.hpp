#pragma once
// API: stable
// Scenes to render: triangle meshes with glTF metallic-roughness materials (from glTF 2.0
// files), analytic spheres (the built-in scenes), analytic lights, and an optional camera.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "ibl/core/image.hpp"
#include "ibl/render/light.hpp"

namespace ibl {

// How a texture is read outside [0, 1] and between texels (a glTF sampler, glTF 2.0 5.26).
enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };
struct TextureSampler {
  Wrap wrapS = Wrap::Repeat, wrapT = Wrap::Repeat;
  bool nearest = false;  // magnification: nearest texel (NEAREST), else bilinear (LINEAR)
  bool mipmaps = true;   // minification reads mip levels (the viewer; the renderer supersamples)
  bool operator==(const TextureSampler&) const = default;
};

// A glTF texture: 8-bit RGBA texels as stored (several textures may share one image) and its
// sampler.
struct Texture {
  int width = 0, height = 0;                              // texels
  std::shared_ptr<const std::vector<std::uint8_t>> rgba;  // 4 bytes per texel, row by row
  TextureSampler sampler;

  bool empty() const { return !rgba || rgba->empty(); }
  // The filtered value at uv (bilinear, or nearest), wrapped as the sampler says. With srgb
  // (base color and emission, glTF 2.0 3.9.2), each texel's RGB is decoded to linear before
  // filtering, as an sRGB texture format does on a GPU; alpha and other textures are linear.
  // uv: glTF texture coordinates ((0, 0) the image's top-left corner, 1 its width or height);
  // returns RGBA in [0, 1], (1, 1, 1, 1) for an empty texture.
  glm::vec4 sample(glm::vec2 uv, bool srgb) const;
};

// KHR_texture_transform on a texture slot: the UVs are scaled, then turned counterclockwise by
// `rotation` radians about the origin, then offset (shared::uvTransformOf in
// ibl/shared/material.h gives the map). The defaults leave them as they are.
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;
  glm::vec2 scale{1.0f};

  bool identity() const {
    return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f);
  }
};

// One texture slot of a material: the scene's texture (-1: none), which UV set it reads (the
// transform's texCoord, where it has one, already applied) and how its UVs are transformed.
struct TextureRef {
  int index = -1;
  int texCoord = 0;  // 0: TEXCOORD_0, 1: TEXCOORD_1
  TextureTransform transform;
};

// How a material's alpha covers what is behind it (the values of shared::alphaCovers).
enum class AlphaMode { Opaque = 0, Mask = 1, Blend = 2 };

// glTF 2.0 metallic-roughness material.
struct Material {
  glm::vec3 baseColor{1.0f};    // linear, 0 to 1
  TextureRef baseColorTexture;  // sRGB; its A multiplies baseColorAlpha
  float baseColorAlpha = 1.0f;  // baseColorFactor's A
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;             // with AlphaMode::Mask
  float metallic = 1.0f;                // 0 to 1
  float roughness = 1.0f;               // perceptual, 0 to 1
  TextureRef metallicRoughnessTexture;  // B = metallic, G = roughness (linear)
  TextureRef normalTexture;
  float normalScale = 1.0f;        // scales the normal map's X and Y (glTF normalTextureInfo.scale)
  TextureRef occlusionTexture;     // R
  float occlusionStrength = 1.0f;  // 0 (none) to 1 (all of the texture's occlusion)
  // emissiveFactor times KHR_materials_emissive_strength: linear radiance, the output's units.
  glm::vec3 emissive{0.0f};
  TextureRef emissiveTexture;  // sRGB
  // KHR_materials_sheen: a Charlie sheen layer over the rest (sheenColor 0: none).
  glm::vec3 sheenColor{0.0f};        // linear
  TextureRef sheenColorTexture;      // sRGB; RGB multiplies sheenColor
  float sheenRoughness = 0.0f;       // perceptual
  TextureRef sheenRoughnessTexture;  // A multiplies sheenRoughness
  // KHR_materials_ior: the dielectric's index of refraction (>= 1, or 0: infinite).
  float ior = 1.5f;
  // KHR_materials_specular: the dielectric's specular strength and F0 color (shared::
  // specularReflectance).
  float specular = 1.0f;
  TextureRef specularTexture;       // A multiplies specular
  glm::vec3 specularColor{1.0f};    // linear; may exceed 1
  TextureRef specularColorTexture;  // sRGB; RGB multiplies specularColor
  // KHR_materials_clearcoat: a second GGX lobe of IOR 1.5 over everything else (the emission
  // included), which it attenuates by its Fresnel (shared::clearcoatWeight). clearcoat 0: none.
  float clearcoat = 0.0f;                // 0 to 1
  TextureRef clearcoatTexture;           // R multiplies clearcoat
  float clearcoatRoughness = 0.0f;       // perceptual, 0 to 1
  TextureRef clearcoatRoughnessTexture;  // G multiplies clearcoatRoughness
  TextureRef clearcoatNormalTexture;     // none: the coat follows the unmapped normal
  float clearcoatNormalScale = 1.0f;     // as normalScale
  // KHR_materials_iridescence: a thin dielectric film whose Fresnel replaces the specular lobe's
  // by `iridescence` (shared::withIridescence, fresnelOf). iridescence 0: none.
  float iridescence = 0.0f;                    // 0 to 1
  TextureRef iridescenceTexture;               // R multiplies iridescence
  float iridescenceIor = 1.3f;                 // the film's index of refraction
  float iridescenceThicknessMinimum = 100.0f;  // nm
  float iridescenceThicknessMaximum = 400.0f;  // nm
  TextureRef iridescenceThicknessTexture;      // G mixes minimum (0) to maximum (1); none: 1
  // KHR_materials_anisotropy: GGX's roughness stretched along a direction of the tangent frame
  // (shared::anisotropicAlpha): anisotropy 0: none.
  float anisotropy = 0.0f;          // 0 to 1, the strength
  float anisotropyRotation = 0.0f;  // radians, counterclockwise from the tangent
  TextureRef anisotropyTexture;     // RG the direction in [-1, 1], B multiplies the strength
  // KHR_materials_transmission: the share of the light below the specular layer that the surface
  // transmits instead of diffusing (shared::withTransmission). transmission 0: none.
  float transmission = 0.0f;       // 0 to 1
  TextureRef transmissionTexture;  // R multiplies transmission
  // KHR_materials_volume: thickness 0 is a thin wall; above it the mesh bounds a volume that
  // refracts (by `ior`) and absorbs by Beer-Lambert (shared::volumeAttenuationCoefficient).
  float thickness = 0.0f;       // the mesh's units, for the real-time paths
  TextureRef thicknessTexture;  // G multiplies thickness
  float attenuationDistance =
      std::numeric_limits<float>::infinity();  // scene units, > 0 (infinite: no absorption)
  glm::vec3 attenuationColor{1.0f};            // linear, what is left after attenuationDistance
  // KHR_materials_unlit, as the loader converts it: the emission is the base color (and its
  // texture), so COLOR_0 multiplies the emission as it would the base color.
  bool unlit = false;

  // Its texture slots in the order of the device's bindings and records (MaterialBinding in
  // ibl/shared/view_bindings.h): base color, metallic-roughness, normal, occlusion, emissive,
  // sheen color, sheen roughness, specular, specular color, clear coat, its roughness, its normal,
  // iridescence, its thickness, anisotropy, transmission, thickness.
  static constexpr std::size_t kTextureSlots = 17;
  std::array<TextureRef, kTextureSlots> textureSlots() const {
    return {baseColorTexture,
            metallicRoughnessTexture,
            normalTexture,
            occlusionTexture,
            emissiveTexture,
            sheenColorTexture,
            sheenRoughnessTexture,
            specularTexture,
            specularColorTexture,
            clearcoatTexture,
            clearcoatRoughnessTexture,
            clearcoatNormalTexture,
            iridescenceTexture,
            iridescenceThicknessTexture,
            anisotropyTexture,
            transmissionTexture,
            thicknessTexture};
  }
};

// Triangles in world space.
struct Mesh {
  std::vector<glm::vec3> positions;  // scene units (meters for glTF)
  std::vector<glm::vec3> normals;    // per vertex, unit
  std::vector<glm::vec4> tangents;   // per vertex, w = handedness (empty: no normal map)
  std::vector<glm::vec2> uvs;        // TEXCOORD_0 (empty: no textures)
  std::vector<glm::vec2> uvs1;       // TEXCOORD_1 (empty: none)
  // COLOR_0, linear RGBA (alpha 1 for a VEC3 accessor; empty: none): multiplies the base color
  // and its alpha, as glTF's baseColorFactor and texture do.
  std::vector<glm::vec4> colors;
  std::vector<std::uint32_t> indices;  // three per triangle, into the vertex arrays
  int material = 0;                    // index into Scene::materials
  // KHR_materials_volume: the scale of the node the mesh was placed by, which multiplies the
  // material's thickness (given in the mesh's own units): the cube root of its world matrix's
  // determinant (the volume's scale; for a uniform scale, that scale).
  float thicknessScale = 1.0f;
  // The names it answers to (--exclude): its glTF mesh's, its node's and that node's ancestors'
  // (unnamed ones left out).
  std::vector<std::string> names;
};

struct Sphere {
  glm::vec3 center{0.0f};  // world, scene units
  float radius = 1.0f;     // scene units
  int material = 0;        // index into Scene::materials
};

struct CameraDescription {
  bool perspective = true;
  float yfovRadians = 0.8f;  // vertical field of view
  float xmag = 1.0f;         // orthographic half width, scene units
  glm::mat4 world{1.0f};     // camera to world; camera looks down its -Z, +Y up
};

struct Scene {
  std::vector<Mesh> meshes;
  std::vector<Sphere> spheres;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::optional<CameraDescription> camera;
  std::vector<Light> lights;  // analytic lights (glTF KHR_lights_punctual, --lights files)

  // Axis-aligned bounds (min, max) of everything, world space.
  std::pair<glm::vec3, glm::vec3> bounds() const;
};

// Whether any material of `scene` has a sheen layer (KHR_materials_sheen: a sheenColor other
// than 0), so that its render needs the bake's sheen chain and table (BakeOptions::sheen).
bool hasSheen(const Scene& scene);

// Whether any material of `scene` lets light through (KHR_materials_transmission: a factor above
// 0), so that its real-time paths draw the opaque frame behind it and filter its shadows.
bool hasTransmission(const Scene& scene);

// The scene without the meshes that answer to any of `names` (Mesh::names: a glTF mesh, or a
// node and everything below it), as a probe capture leaves out dynamic objects. Throws
// UsageError("<option>: ...") when a name matches no mesh or nothing would be left.
Scene withoutObjects(const Scene& scene, const std::vector<std::string>& names,
                     const std::string& option);

// One sphere of radius 1 at the origin, with `material` (no lights, no camera).
Scene makeSphereScene(const Material& material);
// Spheres of roughness 0..1 (columns, left to right) x metallic 1 (top row) and 0 (bottom),
// radius 1, 2.5 apart, centered on the origin in the XY plane, each with `base`'s other
// parameters (base color, ior, specular, sheen).
Scene makeSphereGrid(const Material& base, int columns = 6);
// The grid of spheres of one base color (linear, 0 to 1) and glTF's other defaults.
Scene makeSphereGrid(glm::vec3 baseColor, int columns = 6);

// A sphere as triangles for a rasterizer: `segments` around, segments / 2 from pole to pole,
// vertices on the sphere with exact normals (at least 3 segments and 2 rings).
Mesh tessellateSphere(const Sphere& sphere, int segments);

}  // namespace ibl
