#pragma once
// API: stable
// glTF 2.0 scenes for the renderer and the viewer, and what `ibl info` reports of them.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "ibl/render/scene.hpp"

namespace ibl {

// How a file is read. What ibl can render without (a missing or unreadable texture, an
// extension it does not implement, triangle strips) is a warning, or with `strict` an Error.
// The library prints nothing: each warning goes to `warn`, one line "<path>: <problem>; <what ibl
// does instead>".
struct GltfLoadOptions {
  bool strict = false;
  std::function<void(const std::string&)> warn;  // none: warnings are dropped
  // Limits on what a file can make ibl allocate beyond its own size (docs/scenes.md): the
  // triangles and vertices of the scene as ibl stores them (every instance of a mesh counted),
  // and the decoded texels of its textures.
  std::uint64_t maxGeometryBytes = std::uint64_t{8} << 30;  // bytes
  std::uint64_t maxTextureBytes = std::uint64_t{8} << 30;   // bytes
  // KHR_materials_variants: the variant whose materials the primitives it maps are drawn with
  // (the others keep their own); empty: every primitive its own material. A name the file does
  // not have is an Error that lists the names it has.
  std::string variant;
};

// Reads a glTF 2.0 file (.gltf with external or embedded buffers, .glb), applying node
// transforms; KHR_draco_mesh_compression and EXT_meshopt_compression are decoded; missing normals
// and tangents are generated. Every count, offset, stride and index is checked before anything
// is allocated for it. Throws Error("<path>: ...") for anything it cannot read. Positions in
// the file's units (meters); lights (KHR_lights_punctual) in cd and lx, as the file states them.
Scene loadGltf(const std::string& path, const GltfLoadOptions& options = {});
// The same from bytes already in memory: `path` names the file in messages and is where its
// external buffers and images are looked for.
Scene loadGltf(std::span<const std::uint8_t> bytes, const std::string& path,
               const GltfLoadOptions& options = {});

// What a glTF file holds, as `ibl info` reports it. Indices are the file's. The scene is the one
// loadGltf renders (the file's "scene", else its first, else every root node).
struct GltfSummary {
  bool binary = false;  // a .glb container
  std::string generator;
  std::vector<std::string> extensionsUsed, extensionsRequired;
  int scene = -1;  // -1: the file has no scenes (its root nodes are rendered)
  std::size_t scenes = 0;
  std::vector<std::string> variants;  // KHR_materials_variants' names, in the file's order

  struct Node {
    std::string name;
    int mesh = -1, camera = -1, light = -1, parent = -1;
    bool inScene = false;  // reached from the rendered scene's roots
  };
  struct Mesh {
    std::string name;
    std::size_t primitives = 0;
    std::size_t trianglePrimitives = 0;         // the others (points, lines, strips) are not read
    std::uint64_t triangles = 0, vertices = 0;  // of one instance, vertices the triangles use
    std::size_t instances = 0;                  // nodes of the scene that place it
    std::vector<std::string> compression;       // KHR_draco_mesh_compression, EXT_meshopt_...
    bool vertexColors = false;                  // a primitive has COLOR_0 (multiplies the base)
  };
  struct Material {
    std::string name;
    glm::vec4 baseColor{1.0f};                // baseColorFactor, linear RGBA
    float metallic = 1.0f, roughness = 1.0f;  // factors; roughness perceptual
    glm::vec3 emissive{0.0f};  // emissiveFactor times KHR_materials_emissive_strength
    std::string alphaMode = "OPAQUE";
    bool doubleSided = false;
    std::vector<int> textures;  // the textures its slots read, in slot order, without repeats
    std::vector<std::string> transformedSlots;  // slots with KHR_texture_transform
    std::vector<std::string> extensions;        // every extension on it
    std::vector<std::string> unsupported;       // those of them ibl does not render
    // KHR_materials_ior and KHR_materials_specular (their defaults when absent), and the
    // dielectric's Fresnel reflectance they make (shared::specularReflectance at metallic 0).
    float ior = 1.5f, specular = 1.0f;
    glm::vec3 specularColor{1.0f};
    glm::vec3 dielectricF0{0.04f};
    float dielectricF90 = 1.0f;
    // KHR_materials_clearcoat's factors (0 when absent: no coat).
    float clearcoat = 0.0f, clearcoatRoughness = 0.0f;
    // KHR_materials_iridescence's factors (factor 0 when absent: no film; thicknesses in nm).
    float iridescence = 0.0f, iridescenceIor = 1.3f;
    float iridescenceThicknessMinimum = 100.0f, iridescenceThicknessMaximum = 400.0f;
    // KHR_materials_anisotropy's factors (strength 0 when absent: none; rotation in radians).
    float anisotropy = 0.0f, anisotropyRotation = 0.0f;
    // KHR_materials_transmission's and _volume's factors (transmission 0 when absent: none;
    // thickness 0: a thin wall; the distance infinite: no absorption).
    float transmission = 0.0f, thickness = 0.0f;
    float attenuationDistance = std::numeric_limits<float>::infinity();
    glm::vec3 attenuationColor{1.0f};
  };
  struct Texture {
    int image = -1;      // -1: none that ibl can read
    std::string source;  // the image's file name, "data URI" or "buffer view N"
    std::string mimeType;
    int width = 0, height = 0;  // pixels
    std::string problem;        // empty: readable; else "missing" or why it cannot be read
    bool used = false;          // read by a material slot that ibl renders
  };
  struct Light {
    std::string name, type;  // KHR_lights_punctual: point, spot, directional
    double intensity = 1.0;  // cd (point, spot), lx (directional)
    glm::vec3 color{1.0f};   // linear
    double range = 0.0;      // scene units; 0: none
    double innerConeAngle = 0.0, outerConeAngle = 0.0;  // spot, radians
    std::size_t instances = 0;
  };
  struct Camera {
    std::string name, type;  // perspective, orthographic
    // As the file holds them: yfov radians, aspectRatio width / height, xmag and ymag
    // (half extents), znear and zfar in scene units; 0 where the file gives none.
    double yfov = 0.0, aspectRatio = 0.0, xmag = 0.0, ymag = 0.0, znear = 0.0, zfar = 0.0;
    std::size_t instances = 0;
  };
  std::vector<Node> nodes;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Light> lights;
  std::vector<Camera> cameras;
  // The rendered scene: every instance of every triangle primitive, and its world-space bounds.
  std::size_t meshInstances = 0;
  std::uint64_t triangles = 0, vertices = 0;
  bool hasBounds = false;
  glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};  // world space, scene units
  std::vector<std::string> warnings;           // as loadGltf would report them, without the path
};

// Reads and checks the file as loadGltf does (the same errors), without decoding textures.
GltfSummary describeGltf(const std::string& path, const GltfLoadOptions& options = {});
GltfSummary describeGltf(std::span<const std::uint8_t> bytes, const std::string& path,
                         const GltfLoadOptions& options = {});

}  // namespace ibl
