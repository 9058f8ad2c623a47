// The checks: every reference, count, offset and stride of the file against what it refers to,
// with overflow-safe arithmetic, before anything is allocated for it; the accessors' layouts.
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "document.hpp"

namespace ibl::gltf {

// An integer member of an extension's object, checked: nullopt when absent.
std::optional<int> extensionIndex(const tinygltf::Value& o, const char* key,
                                  const std::string& path, const std::string& where) {
  if (!o.IsObject() || !o.Has(key)) return std::nullopt;
  const tinygltf::Value& v = o.Get(key);
  if (v.IsInt()) return v.Get<int>();
  if (v.IsReal()) {
    const double d = v.Get<double>();
    if (d == std::floor(d) && std::abs(d) < 2e9) return static_cast<int>(d);
  }
  fail(path, fmt::format("{}: {} is not an integer", where, key));
}

void GltfDocument::validate() {
  validateBufferViews();
  layouts_.resize(accessors().size());
  for (std::size_t k = 0; k < accessors().size(); ++k) layouts_[k] = validateAccessor(k);
  for (std::size_t k = 0; k < images_.size(); ++k)
    if (images_[k].bufferView >= 0 && !inRange(images_[k].bufferView, model_.bufferViews.size()))
      error(
          fmt::format("image {}: {}", k,
                      outOfRange("buffer view", images_[k].bufferView, model_.bufferViews.size())));
  for (std::size_t t = 0; t < model_.textures.size(); ++t) {
    const tinygltf::Texture& g = model_.textures[t];
    if (g.source != -1 && !inRange(g.source, images_.size()))
      error(fmt::format("texture {}: {}", t, outOfRange("image", g.source, images_.size())));
    if (const int webp = textureImage(static_cast<int>(t));
        webp != -1 && !inRange(webp, images_.size()))
      error(fmt::format("texture {}: EXT_texture_webp source: {}", t,
                        outOfRange("image", webp, images_.size())));
    if (g.sampler != -1 && !inRange(g.sampler, model_.samplers.size()))
      error(fmt::format("texture {}: {}", t,
                        outOfRange("sampler", g.sampler, model_.samplers.size())));
  }
  for (std::size_t k = 0; k < model_.materials.size(); ++k) validateMaterial(k);
  for (std::size_t m = 0; m < model_.meshes.size(); ++m)
    for (std::size_t p = 0; p < model_.meshes[m].primitives.size(); ++p) validatePrimitive(m, p);
  validateVariants();
  validateNodes();
}

void GltfDocument::validateBufferViews() {
  for (std::size_t v = 0; v < model_.bufferViews.size(); ++v) {
    const tinygltf::BufferView& bv = model_.bufferViews[v];
    const std::string where = fmt::format("buffer view {}", v);
    if (!inRange(bv.buffer, model_.buffers.size()))
      error(where + ": " + outOfRange("buffer", bv.buffer, model_.buffers.size()));
    const std::size_t size = model_.buffers[static_cast<std::size_t>(bv.buffer)].data.size();
    if (bv.byteOffset > size || bv.byteLength > size - bv.byteOffset)
      error(fmt::format("{}: bytes {} to {} lie past the end of buffer {} ({} bytes)", where,
                        bv.byteOffset, saturatingAdd(bv.byteOffset, bv.byteLength), bv.buffer,
                        size));
    if (bv.byteStride != 0 && (bv.byteStride < 4 || bv.byteStride > 252))
      error(fmt::format("{}: byteStride {} (glTF allows 4 to 252)", where, bv.byteStride));
  }
}

const tinygltf::BufferView& GltfDocument::bufferView(const std::string& where, int v) const {
  if (!inRange(v, model_.bufferViews.size()))
    error(where + ": " + outOfRange("buffer view", v, model_.bufferViews.size()));
  return model_.bufferViews[static_cast<std::size_t>(v)];
}

const std::uint8_t* GltfDocument::viewRange(const std::string& where, int v, u64 offset, u64 count,
                                            u64 size, u64 stride) const {
  const tinygltf::BufferView& bv = bufferView(where, v);
  if (count > 0 && (offset > bv.byteLength || bv.byteLength - offset < size ||
                    (count - 1) > (bv.byteLength - offset - size) / stride))
    error(
        fmt::format("{}: {} elements of {} bytes, {} apart, from byte {} of buffer view {} "
                    "read past its end ({} bytes)",
                    where, count, size, stride, offset, v, bv.byteLength));
  return model_.buffers[static_cast<std::size_t>(bv.buffer)].data.data() + bv.byteOffset +
         std::min<u64>(offset, bv.byteLength);
}

AccessorLayout GltfDocument::validateAccessor(std::size_t k) const {
  const tinygltf::Accessor& a = accessors()[k];
  const std::string where = fmt::format("accessor {}", k);
  AccessorLayout l;
  const std::size_t cs = componentSize(a.componentType);
  if (cs == 0)
    error(fmt::format("{}: componentType {} is not a glTF component type", where, a.componentType));
  const int n = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  if (n <= 0) error(fmt::format("{}: its type is not a glTF accessor type", where));
  l.componentType = a.componentType;
  l.components = n;
  l.normalized = a.normalized;
  l.count = a.count;
  l.matrix = n == 4 ? a.type == TINYGLTF_TYPE_MAT2 : n > 4;
  // Matrix columns start on 4-byte boundaries (glTF 2.0 3.6.2.4).
  const std::size_t rows = n == 4 && l.matrix ? 2 : n == 9 ? 3 : n == 16 ? 4 : 0;
  l.elementSize = rows ? rows * ((rows * cs + 3) / 4 * 4) : static_cast<std::size_t>(n) * cs;
  if (a.bufferView != -1) {
    const tinygltf::BufferView& bv = bufferView(where, a.bufferView);
    l.stride = bv.byteStride ? bv.byteStride : l.elementSize;
    if (l.stride < l.elementSize)
      error(
          fmt::format("{}: buffer view {} has a byteStride of {}, less than one element ({} "
                      "bytes)",
                      where, a.bufferView, l.stride, l.elementSize));
    l.data = viewRange(where, a.bufferView, a.byteOffset, a.count, l.elementSize, l.stride);
  }
  if (a.sparse.isSparse) {
    const auto& s = a.sparse;
    const std::string sparse = where + ": sparse";
    if (s.count < 1 || static_cast<u64>(s.count) > a.count)
      error(fmt::format("{} count {} for {} elements", sparse, s.count, a.count));
    const std::size_t is = componentSize(s.indices.componentType);
    if (s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      error(fmt::format("{} indices: componentType {} is not an unsigned integer type", sparse,
                        s.indices.componentType));
    if (s.indices.byteOffset < 0 || s.values.byteOffset < 0)
      error(fmt::format("{}: a negative byteOffset", sparse));
    const auto count = static_cast<u64>(s.count);
    l.sparseCount = static_cast<std::size_t>(count);
    l.sparseIndexType = s.indices.componentType;
    l.sparseIndices = viewRange(sparse + " indices", s.indices.bufferView,
                                static_cast<u64>(s.indices.byteOffset), count, is, is);
    l.sparseValues =
        viewRange(sparse + " values", s.values.bufferView, static_cast<u64>(s.values.byteOffset),
                  count, l.elementSize, l.elementSize);
    // Increasing (glTF 2.0 3.6.2.3), which the lookups' binary search needs, and in range.
    for (std::size_t i = 0; i < l.sparseCount; ++i) {
      const std::uint32_t at = unsignedAt(l.sparseIndices, l.sparseIndexType, i);
      if (at >= a.count)
        error(fmt::format("{} index {} is element {}, out of range ({} elements)", sparse, i, at,
                          a.count));
      if (i > 0 && at <= unsignedAt(l.sparseIndices, l.sparseIndexType, i - 1))
        error(fmt::format("{} indices are not increasing (index {})", sparse, i));
    }
  }
  return l;
}

void GltfDocument::validateMaterial(std::size_t k) {
  const tinygltf::Material& m = model_.materials[k];
  const std::string where = materialLabel(k);
  if (m.pbrMetallicRoughness.baseColorFactor.size() != 4)
    error(where + ": baseColorFactor does not have 4 components");
  if (!m.emissiveFactor.empty() && m.emissiveFactor.size() != 3)
    error(where + ": emissiveFactor does not have 3 components");
  for (const SlotRef& slot : materialSlots(m, path_, where)) {
    if (slot.index == -1) continue;
    if (!inRange(slot.index, model_.textures.size()))
      error(fmt::format("{}: {}: {}", where, slot.name,
                        outOfRange("texture", slot.index, model_.textures.size())));
    if (slot.texCoord < 0)
      error(fmt::format("{}: {}: texCoord {}", where, slot.name, slot.texCoord));
    usedTextures_.insert(slot.index);
  }
}

void GltfDocument::validatePrimitive(std::size_t m, std::size_t p) {
  const tinygltf::Primitive& prim = model_.meshes[m].primitives[p];
  const std::string where = fmt::format("mesh {} primitive {}", m, p);
  if (prim.material != -1 && !inRange(prim.material, model_.materials.size()))
    error(where + ": " + outOfRange("material", prim.material, model_.materials.size()));
  if (prim.mode < -1 || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
    error(fmt::format("{}: mode {} is not a glTF primitive mode", where, prim.mode));
  for (const auto& [name, accessor] : prim.attributes)
    if (!inRange(accessor, accessors().size()))
      error(fmt::format("{}: {}: {}", where, name,
                        outOfRange("accessor", accessor, accessors().size())));
  if (prim.indices != -1 && !inRange(prim.indices, accessors().size()))
    error(fmt::format("{}: indices: {}", where,
                      outOfRange("accessor", prim.indices, accessors().size())));
  const auto draco = prim.extensions.find("KHR_draco_mesh_compression");
  if (draco != prim.extensions.end()) {
    const std::string at = where + ": KHR_draco_mesh_compression";
    const std::optional<int> view = extensionIndex(draco->second, "bufferView", path_, at);
    if (!view) error(at + " without a bufferView");
    if (!inRange(*view, model_.bufferViews.size()))
      error(at + ": " + outOfRange("buffer view", *view, model_.bufferViews.size()));
    const tinygltf::Value& attributes = draco->second.Get("attributes");
    if (!attributes.IsObject()) error(at + " without attributes");
    for (const std::string& key : attributes.Keys())
      if (extensionIndex(attributes, key.c_str(), path_, at + " attributes").value_or(-1) < 0)
        error(fmt::format("{}: attribute {} has a negative id", at, key));
  }
}

void GltfDocument::validateNodes() {
  const std::size_t count = nodes().size();
  parents_.assign(count, -1);
  for (std::size_t n = 0; n < count; ++n) {
    const tinygltf::Node& node = nodes()[n];
    const std::string where = fmt::format("node {}", n);
    if (node.mesh != -1 && !inRange(node.mesh, model_.meshes.size()))
      error(where + ": " + outOfRange("mesh", node.mesh, model_.meshes.size()));
    if (node.camera != -1 && !inRange(node.camera, model_.cameras.size()))
      error(where + ": " + outOfRange("camera", node.camera, model_.cameras.size()));
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext != node.extensions.end()) {
      const int light = lightIndexOf(node);
      if (light == std::numeric_limits<int>::min() || light == -1)
        error(where + ": KHR_lights_punctual without a light index");
      if (!inRange(light, model_.lights.size()))
        error(where + ": KHR_lights_punctual " + outOfRange("light", light, model_.lights.size()));
    }
    if (!node.matrix.empty() && node.matrix.size() != 16)
      error(fmt::format("{}: matrix has {} numbers, not 16", where, node.matrix.size()));
    if (!node.translation.empty() && node.translation.size() != 3)
      error(fmt::format("{}: translation has {} numbers, not 3", where, node.translation.size()));
    if (!node.rotation.empty() && node.rotation.size() != 4)
      error(fmt::format("{}: rotation has {} numbers, not 4", where, node.rotation.size()));
    if (!node.scale.empty() && node.scale.size() != 3)
      error(fmt::format("{}: scale has {} numbers, not 3", where, node.scale.size()));
    for (const int child : node.children) {
      if (!inRange(child, count)) error(where + ": child " + outOfRange("node", child, count));
      int& parent = parents_[static_cast<std::size_t>(child)];
      if (parent == static_cast<int>(n))
        error(fmt::format("{} lists node {} twice among its children", where, child));
      if (parent != -1)
        error(fmt::format("node {} has two parents (nodes {} and {})", child, parent, n));
      parent = static_cast<int>(n);
    }
  }
  // With one parent each, a node is in a cycle exactly when following parents never ends.
  std::vector<char> state(count, 0);  // 0: unknown, 1: on the current path, 2: reaches a root
  for (std::size_t n = 0; n < count; ++n) {
    std::vector<std::size_t> path;
    std::size_t at = n;
    while (state[at] == 0) {
      state[at] = 1;
      path.push_back(at);
      if (parents_[at] < 0) break;
      at = static_cast<std::size_t>(parents_[at]);
    }
    if (state[at] == 1 && parents_[at] >= 0)
      error(fmt::format("node {} is its own ancestor (a cycle)", at));
    for (std::size_t q : path) state[q] = 2;
  }
  if (model_.defaultScene != -1 && !inRange(model_.defaultScene, model_.scenes.size()))
    error(outOfRange("scene", model_.defaultScene, model_.scenes.size()));
  for (std::size_t s = 0; s < model_.scenes.size(); ++s) {
    std::set<int> seen;
    for (const int n : model_.scenes[s].nodes) {
      const std::string where = fmt::format("scene {}", s);
      if (!inRange(n, count)) error(where + ": " + outOfRange("node", n, count));
      if (parents_[static_cast<std::size_t>(n)] != -1)
        error(fmt::format("{}: node {} is a root of the scene and a child of node {}", where, n,
                          parents_[static_cast<std::size_t>(n)]));
      if (!seen.insert(n).second) error(fmt::format("{}: node {} is listed twice", where, n));
    }
  }
}

}  // namespace ibl::gltf
