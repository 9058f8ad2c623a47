#pragma once
// Internal to the glTF loader: GltfDocument, a glTF 2.0 file read by tinygltf and checked, and
// what is read from it. Its parts live in this folder, one file each, in the order loading runs:
//  1. the container (GLB chunks) and the JSON are checked and prepared for tinygltf
//     (json_filter.cpp: Draco accessors and meshopt fallback buffers hidden, images taken out,
//     external buffers' sizes checked against their byteLength);
//  2. tinygltf parses (container.cpp); EXT_meshopt_compression views are decoded
//     (compression.cpp, with the Draco streams);
//  3. every reference, count, offset and stride is checked against what it refers to
//     (validation.cpp; accessors.cpp reads them) with overflow-safe arithmetic, before anything
//     is allocated for it; the node tree is walked (load_scene.cpp);
//  4. the images the materials read are checked (their headers against their sizes) and
//     decoded (images.cpp; load_materials.cpp); a missing or unreadable one is a warning;
//  5. the scene's memory is estimated from the checked counts and refused over the limit; the
//     primitives are read (load_geometry.cpp, once each, however many nodes place them), then
//     placed in the world with their lights and camera (load_scene.cpp, load_lights.cpp).
// summary.cpp describes the file for `ibl info`; gltf.cpp is the public API
// (include/ibl/render/gltf.hpp). A hostile file thus costs about its own size plus the data of
// what is valid in it.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include <tiny_gltf.h>
#include <glm/mat4x4.hpp>

#include "accessors.hpp"
#include "common.hpp"
#include "ibl/core/error.hpp"
#include "ibl/render/gltf.hpp"
#include "json_filter.hpp"

namespace ibl::gltf {

// What probeImage found in an image's header.
struct ImageProbe {
  int width = 0, height = 0;
  std::string problem;  // empty: readable
};

// A triangle primitive, read in the mesh's space with only the vertices its triangles use.
struct PrimitiveData {
  bool read = false;
  u64 bytes = 0;  // as stored in the Scene (an upper bound until read)
  Mesh mesh;
  std::size_t instancesLeft = 0;
};

// One node of the scene that places a mesh, a camera or a light.
struct Instance {
  int node = 0;
  glm::mat4 world{1.0f};
};

// The material slots ibl reads, as (name, texture info): glTF's five and those of the material
// extensions ibl renders; the texCoord is KHR_texture_transform's where it gives one.
struct SlotRef {
  std::string name;
  int index = -1, texCoord = 0;
  TextureTransform transform;  // KHR_texture_transform (identity: none)
  bool transformed = false;    // the slot has KHR_texture_transform
};

// --- container.cpp ---------------------------------------------------------------------------

// Parses a .gltf or .glb with tinygltf, after prepareJson.
// @param bytes     the file's bytes.
// @param path      the file: named in messages; its folder holds the external buffers.
// @param prepared  receives what prepareJson took out of the JSON (its text emptied).
// @param binary    set when the file is a GLB container.
// @return the model, its buffers loaded. Throws Error("<path>: ...") if tinygltf cannot read it
//         or it requires an extension ibl does not implement.
tinygltf::Model readModel(std::span<const std::uint8_t> bytes, const std::string& path,
                          PreparedJson& prepared, bool& binary);

// Whether ibl renders the extension `ext` (the others in extensionsUsed are a warning each).
bool implemented(std::string_view ext);

// --- compression.cpp -------------------------------------------------------------------------

// Decodes the views hideMeshoptFallbacks listed (EXT_meshopt_compression) into buffers of their
// own, each view pointed at its decoded bytes.
// @param model  the model tinygltf read; buffers are added to it.
// @param views  the compressed views prepareJson listed.
// @param path   the file, for messages; Error("<path>: buffer view N: ...") for a view whose
//               sizes or data are wrong.
void decodeMeshoptViews(tinygltf::Model& model, const std::vector<MeshoptView>& views,
                        const std::string& path);

// The number of triangles a Draco mesh stream's header declares, read without decoding it; 0
// for a header the decoder refuses without allocating.
// @param bytes  the KHR_draco_mesh_compression stream.
u64 dracoDeclaredFaces(std::span<const std::uint8_t> bytes);

// --- validation.cpp --------------------------------------------------------------------------

// An integer member of an extension's object, checked: nullopt when absent.
// @param o      the extension's object (or one of its members).
// @param key    the member's name.
// @param path   the file, for messages.
// @param where  the object, for messages: a value that is not an integer is
//               Error("<path>: <where>: <key> is not an integer").
std::optional<int> extensionIndex(const tinygltf::Value& o, const char* key,
                                  const std::string& path, const std::string& where);

// --- load_materials.cpp ----------------------------------------------------------------------

// The texture slots of a material, in slot order (absent slots have index -1).
// @param m      the material.
// @param path   the file, for messages.
// @param where  the material, for messages ("material 3").
std::vector<SlotRef> materialSlots(const tinygltf::Material& m, const std::string& path,
                                   const std::string& where);

// The factors of the material extensions ibl renders (KHR_materials_sheen, _ior, _specular),
// written into `mat` (textures left as they are). Throws Error naming `path` and `where` for a
// factor outside the range its specification allows.
void readExtensionFactors(const tinygltf::Material& m, const std::string& path,
                          const std::string& where, Material& mat);

// The document: the model, checked, and what is read from it.
class GltfDocument {
 public:
  // Reads and checks the file (gltf.cpp): steps 1 to 3 above.
  // @param bytes    the file's bytes.
  // @param path     the file: named in messages, its folder holding external buffers and images.
  // @param options  strictness, the warnings' receiver and the memory limits.
  GltfDocument(std::span<const std::uint8_t> bytes, const std::string& path,
               const GltfLoadOptions& options);

  // The scene the file renders: textures decoded, materials, meshes placed in the world, the
  // first camera and the lights (load_scene.cpp). Throws Error for a scene without triangles.
  Scene load();

  // What a mesh instance of `node` answers to: the glTF mesh's name, the node's and its
  // ancestors' (unnamed ones left out).
  std::vector<std::string> namesOf(int node) const;

  // What the file holds, as `ibl info` reports it (summary.cpp): every mesh read, textures
  // checked but not decoded.
  GltfSummary describe();

 private:
  const std::vector<tinygltf::Node>& nodes() const { return model_.nodes; }
  const std::vector<tinygltf::Accessor>& accessors() const { return model_.accessors; }

  // A warning, or with strict an error: `problem`, then what ibl does instead.
  void warn(const std::string& problem, const std::string& instead);

  [[noreturn]] void error(const std::string& problem) const { fail(path_, problem); }

  static std::string materialLabel(std::size_t k) { return fmt::format("material {}", k); }

  // --- 3. Checks (validation.cpp) -----------------------------------------------------------

  // Every reference, count, offset and stride checked; the accessors' layouts made.
  void validate();
  void validateBufferViews();

  // Buffer view `v`, which `where` refers to, checked to exist.
  const tinygltf::BufferView& bufferView(const std::string& where, int v) const;

  // Checks that `count` elements of `size` bytes, `stride` apart, from `offset` fit in view `v`;
  // returns their address.
  const std::uint8_t* viewRange(const std::string& where, int v, u64 offset, u64 count, u64 size,
                                u64 stride) const;

  // Accessor `k` checked: its types, its elements within its view, its sparse indices
  // increasing and in range.
  AccessorLayout validateAccessor(std::size_t k) const;
  void validateMaterial(std::size_t k);
  void validatePrimitive(std::size_t m, std::size_t p);

  // KHR_materials_variants (variants.cpp): the variants' names and every primitive's mappings
  // checked (materials and variants in range), and GltfLoadOptions::variant found among them
  // (an Error naming the file's variants when it is not).
  void validateVariants();
  // The material primitive p of mesh m is drawn with: the chosen variant's, else its own (-1:
  // none).
  int materialOf(int m, std::size_t p) const;

  // Every index a node holds is in range, and the nodes form disjoint trees (glTF 2.0 3.5.1:
  // no node has two parents, no cycles), so the scene is walked once per node.
  void validateNodes();

  // The rendered scene's nodes in depth-first order (children in order), with their world
  // transforms: the instances of meshes and lights, and the first camera (load_scene.cpp).
  void walkScene();

  // One warning for each extension the file uses that ibl does not render (container.cpp).
  void warnAboutExtensions();

  // --- 4. Images (images.cpp) and materials (load_materials.cpp) ----------------------------

  struct ImageState {
    bool probed = false, missing = false;
    ImageProbe probe;
    std::string key;  // the same key: the same bytes (decoded once)
  };

  // Where an image's bytes are: its file name, "data URI" or "buffer view N".
  std::string sourceName(int image) const;

  // "texture 'wood.png' (image 2)", "texture image 2 (buffer view 5)"
  std::string imageLabel(int image) const;

  // The image's bytes (empty when missing: `missing` set, or unreadable: `problem` set).
  std::span<const std::uint8_t> imageBytes(int image, ImageState& st);

  // The image's state, its header probed the first time it is asked for.
  const ImageState& imageState(int image);

  // Why texture `texture` has no image ibl reads ("no image", or the extensions it has).
  std::string noSourceProblem(int texture) const;

  // The image texture `texture` shows: EXT_texture_webp's source where the texture has one (the
  // core `source` is then its fallback), else its `source` (-1: none).
  int textureImage(int texture) const;

  // The textures, one per glTF texture; those the materials read decoded (with `decode`) or
  // only checked. A missing or unreadable image is a warning and its textures are empty.
  std::vector<Texture> readTextures(bool decode);

  // The image decoded to 8-bit RGBA; empty (and a warning) if the decoder fails.
  std::shared_ptr<const std::vector<std::uint8_t>> decodeImage(int image,
                                                               std::span<const std::uint8_t> bytes,
                                                               const ImageProbe& probe);

  // The glTF sampler `index` (-1: glTF's defaults) as a TextureSampler.
  TextureSampler samplerOf(int index) const;

  // emissiveFactor times KHR_materials_emissive_strength.
  static glm::vec3 emissiveOf(const tinygltf::Material& m);

  // The metallic-roughness materials, then a default one (gray, roughness 0.5) for primitives
  // without a material; textures are indices into readTextures' list, -1 for none.
  std::vector<Material> readMaterials(const std::vector<Texture>& textures);

  // --- 5. Geometry (load_geometry.cpp; Draco in compression.cpp) ----------------------------

  // Bytes per vertex and per index as a Scene stores them: position, normal, tangent, two UV
  // sets, a color; one 32-bit index.
  static constexpr u64 kVertexBytes = 12 + 12 + 16 + 8 + 8 + 16, kIndexBytes = 4;
  // Draco's peak while decoding, per triangle its stream declares: the edgebreaker's corner table
  // (24 bytes, measured), its other tables, the attributes' values (up to 3 points a triangle) and
  // the copy into the Scene.
  static constexpr u64 kDracoBytesPerFace = 128;

  // "mesh 2 primitive 0"
  std::string primitiveLabel(int m, std::size_t p) const;

  // The primitive's data (null for what is not a triangle list), read by prepareGeometry.
  PrimitiveData* primitive(int m, std::size_t p);

  // Sizes each triangle primitive of the meshes with uses[m] > 0 (Draco ones by decoding them),
  // refuses a scene larger than the limit (every use counted), then reads them.
  void prepareGeometry(const std::vector<std::size_t>& uses);

  // The accessor of the primitive's attribute `name`; -1 without one.
  int attributeOf(const tinygltf::Primitive& prim, const char* name) const;

  // The bytes a primitive takes in the Scene, at most: its indices, and as many vertices as
  // it has or as its indices name, whichever is fewer.
  u64 estimatePrimitive(int m, std::size_t p) const;

  // Checks an attribute accessor: its type, a component type glTF allows for attributes, and
  // one value per vertex.
  const AccessorLayout& attribute(int m, std::size_t p, const char* name, int accessor,
                                  int components, std::size_t vertices) const;

  // A primitive from its accessors: the indices (checked against the vertex count), the
  // vertices they use (in their order), each attribute's values of those vertices.
  Mesh readPrimitive(int m, std::size_t p) const;

  // Renumbers `indices` to the vertices they use, in the vertices' order; returns the old
  // numbers of the vertices kept. Memory in proportion to the indices, not to `vertices`.
  static std::vector<std::uint32_t> keepUsed(std::vector<std::uint32_t>& indices,
                                             std::size_t vertices);

  // The bytes of a KHR_draco_mesh_compression primitive's stream.
  std::span<const std::uint8_t> dracoBytes(int m, std::size_t p) const;

  // A KHR_draco_mesh_compression primitive: attributes and triangles from the Draco stream.
  Mesh readDracoPrimitive(int m, std::size_t p) const;

  // Positions past float range (a transform's scale, or values of 3e38) would break the bounds
  // and the ray tracer.
  void checkFinite(const Mesh& mesh, int m, std::size_t p, int node) const;

  // COLOR_0's values are finite and not negative (a multiplier of the base color).
  void checkVertexColors(const Mesh& mesh, const std::string& where) const;

  // --- Lights (load_lights.cpp) -------------------------------------------------------------

  // The KHR_lights_punctual light a node places: -1 for none, INT_MIN for a light index that
  // is not an integer.
  static int lightIndexOf(const tinygltf::Node& node);

  // KHR_lights_punctual: a node's light shines down the node's -Z from its origin, in the
  // extension's units (cd for point and spot, lx for directional).
  Light lightOf(const Instance& instance) const;

  std::string path_;
  GltfLoadOptions options_;
  tinygltf::Model model_;
  bool binary_ = false;
  std::vector<ImageSource> images_;
  std::set<int> meshoptViews_;
  std::vector<AccessorLayout> layouts_;
  std::set<int> usedTextures_;
  std::vector<int> parents_;
  std::vector<bool> inScene_;
  int sceneIndex_ = -1;
  std::vector<Instance> instances_, lightInstances_;
  std::optional<std::pair<int, glm::mat4>> camera_;
  std::vector<std::vector<std::optional<PrimitiveData>>> primitives_;
  std::vector<std::string> warnings_;
  bool warnedStrips_ = false;
  std::vector<std::uint8_t> ownedBytes_;  // the bytes imageBytes read last (a file, a data URI)
  std::map<int, ImageState> imageStates_;
  std::vector<std::string> variants_;  // KHR_materials_variants' names
  std::map<std::tuple<int, std::size_t, int>, int> variantMaterials_;  // (mesh, primitive, variant)
  int variant_ = -1;                                                   // the chosen one (-1: none)
};

}  // namespace ibl::gltf
