// Geometry: each triangle primitive sized from its checked counts (Draco's from its stream's
// header), the scene refused over the memory limit (every instance counted), then read from its
// accessors, keeping only the vertices its triangles use.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "document.hpp"

namespace ibl::gltf {

std::string GltfDocument::primitiveLabel(int m, std::size_t p) const {
  return fmt::format("mesh {} primitive {}", m, p);
}

PrimitiveData* GltfDocument::primitive(int m, std::size_t p) {
  auto& prims = primitives_[static_cast<std::size_t>(m)];
  return p < prims.size() && prims[p] ? &*prims[p] : nullptr;
}

void GltfDocument::prepareGeometry(const std::vector<std::size_t>& uses) {
  primitives_.assign(model_.meshes.size(), {});
  u64 total = 0;
  std::vector<std::pair<std::size_t, std::size_t>> draco;
  for (std::size_t m = 0; m < model_.meshes.size(); ++m) {
    if (uses[m] == 0) continue;
    const auto& prims = model_.meshes[m].primitives;
    primitives_[m].resize(prims.size());
    for (std::size_t p = 0; p < prims.size(); ++p) {
      const tinygltf::Primitive& prim = prims[p];
      if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP || prim.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        if (!warnedStrips_) {
          warnedStrips_ = true;
          warn(fmt::format("{} holds triangle {}, which ibl does not read",
                           primitiveLabel(static_cast<int>(m), p),
                           prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP ? "strips" : "fans"),
               "rendering without them");
        }
        continue;
      }
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;  // points, lines
      PrimitiveData& data = primitives_[m][p].emplace();
      data.instancesLeft = uses[m];
      if (prim.extensions.count("KHR_draco_mesh_compression")) {
        draco.emplace_back(m, p);
        continue;
      }
      data.bytes = estimatePrimitive(static_cast<int>(m), p);
      total = saturatingAdd(total, saturatingMul(data.bytes, uses[m]));
    }
  }
  // Draco primitives: each decoding's peak counted first, from the triangles its stream
  // declares; then its data, as decoded.
  for (const auto& [m, p] : draco) {
    const u64 faces = dracoDeclaredFaces(dracoBytes(static_cast<int>(m), p));
    const u64 decoding = saturatingMul(faces, kDracoBytesPerFace);
    if (saturatingAdd(total, decoding) > options_.maxGeometryBytes)
      error(
          fmt::format("{}: KHR_draco_mesh_compression: its stream declares {} triangles, whose "
                      "decoding takes up to {}: past the limit of {} with the rest of the "
                      "scene",
                      primitiveLabel(static_cast<int>(m), p), faces, formatBytes(decoding),
                      formatBytes(options_.maxGeometryBytes)));
    PrimitiveData& data = *primitives_[m][p];
    data.mesh = readDracoPrimitive(static_cast<int>(m), p);
    data.read = true;
    data.bytes = kIndexBytes * data.mesh.indices.size() + kVertexBytes * data.mesh.positions.size();
    total = saturatingAdd(total, saturatingMul(data.bytes, uses[m]));
  }
  if (total > options_.maxGeometryBytes)
    error(
        fmt::format("its scene holds up to {} of triangles and vertices as ibl stores them "
                    "(every instance counted), more than the limit of {}",
                    formatBytes(total), formatBytes(options_.maxGeometryBytes)));
  for (std::size_t m = 0; m < primitives_.size(); ++m)
    for (std::size_t p = 0; p < primitives_[m].size(); ++p)
      if (primitives_[m][p] && !primitives_[m][p]->read) {
        primitives_[m][p]->mesh = readPrimitive(static_cast<int>(m), p);
        primitives_[m][p]->read = true;
      }
}

int GltfDocument::attributeOf(const tinygltf::Primitive& prim, const char* name) const {
  const auto it = prim.attributes.find(name);
  return it == prim.attributes.end() ? -1 : it->second;
}

u64 GltfDocument::estimatePrimitive(int m, std::size_t p) const {
  const tinygltf::Primitive& prim = model_.meshes[static_cast<std::size_t>(m)].primitives[p];
  const int position = attributeOf(prim, "POSITION");
  if (position < 0) error(primitiveLabel(m, p) + " has no POSITION");
  const u64 vertices = layouts_[static_cast<std::size_t>(position)].count;
  const u64 indices =
      prim.indices >= 0 ? layouts_[static_cast<std::size_t>(prim.indices)].count : vertices;
  return saturatingAdd(saturatingMul(kIndexBytes, indices),
                       saturatingMul(kVertexBytes, std::min(vertices, indices)));
}

const AccessorLayout& GltfDocument::attribute(int m, std::size_t p, const char* name, int accessor,
                                              int components, std::size_t vertices) const {
  const AccessorLayout& a = layouts_[static_cast<std::size_t>(accessor)];
  const std::string where = fmt::format("{}: {} accessor {}", primitiveLabel(m, p), name, accessor);
  if (a.components != components || a.matrix)
    error(fmt::format("{} is {}, not {}", where, typeName(a.components), typeName(components)));
  if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    error(where + " has 32-bit integer components, which glTF does not allow for attributes");
  if (vertices != kU64Max && a.count != vertices)
    error(fmt::format("{} has {} values for {} positions", where, a.count, vertices));
  return a;
}

Mesh GltfDocument::readPrimitive(int m, std::size_t p) const {
  const tinygltf::Primitive& prim = model_.meshes[static_cast<std::size_t>(m)].primitives[p];
  const std::string where = primitiveLabel(m, p);
  const AccessorLayout& pos =
      attribute(m, p, "POSITION", attributeOf(prim, "POSITION"), 3, kU64Max);
  const std::size_t vertices = pos.count;
  if (vertices > std::numeric_limits<std::uint32_t>::max())
    error(fmt::format("{}: POSITION has {} vertices, more than 32-bit indices reach", where,
                      vertices));
  struct Optional {
    const char* name;
    int components;
    const AccessorLayout* layout = nullptr;
  };
  Optional optional[] = {{"NORMAL", 3}, {"TANGENT", 4}, {"TEXCOORD_0", 2}, {"TEXCOORD_1", 2}};
  for (Optional& o : optional) {
    const int k = attributeOf(prim, o.name);
    if (k >= 0) o.layout = &attribute(m, p, o.name, k, o.components, vertices);
  }
  // COLOR_0: VEC3 or VEC4 (float, or normalized unsigned bytes or shorts).
  const AccessorLayout* color = nullptr;
  if (const int k = attributeOf(prim, "COLOR_0"); k >= 0) {
    const bool rgb = layouts_[static_cast<std::size_t>(k)].components == 3;
    color = &attribute(m, p, "COLOR_0", k, rgb ? 3 : 4, vertices);
    if (color->componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !color->normalized)
      error(fmt::format("{}: COLOR_0 accessor {} has integer components that are not normalized",
                        where, k));
  }
  Mesh mesh;
  if (prim.indices >= 0) {
    const AccessorLayout& idx = layouts_[static_cast<std::size_t>(prim.indices)];
    if (idx.components != 1 || (idx.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                idx.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                                idx.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
      error(fmt::format("{}: index accessor {} is not of unsigned integer scalars", where,
                        prim.indices));
    if (idx.count % 3)
      error(fmt::format("{}: {} indices, not a whole number of triangles", where, idx.count));
    mesh.indices.resize(idx.count);
    for (std::size_t i = 0; i < idx.count; ++i) {
      const std::uint32_t v = readIndex(idx, i);
      if (v >= vertices)
        error(fmt::format("{}: index {} is vertex {}, out of range (POSITION has {})", where, i, v,
                          vertices));
      mesh.indices[i] = v;
    }
  } else {
    if (vertices % 3)
      error(fmt::format("{}: {} vertices, not a whole number of triangles", where, vertices));
    mesh.indices.resize(vertices);
    for (std::size_t i = 0; i < vertices; ++i) mesh.indices[i] = static_cast<std::uint32_t>(i);
  }
  // The vertices the triangles use, in their order (exporters often share one vertex buffer
  // between primitives that each draw a part of it: each would otherwise keep all of it).
  const std::vector<std::uint32_t> kept = keepUsed(mesh.indices, vertices);
  const auto gather = [&](const AccessorLayout& a, auto& out) {
    out.resize(kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i) readFloats(a, kept[i], &out[i][0]);
  };
  gather(pos, mesh.positions);
  if (optional[0].layout) gather(*optional[0].layout, mesh.normals);
  if (optional[1].layout) gather(*optional[1].layout, mesh.tangents);
  if (optional[2].layout) gather(*optional[2].layout, mesh.uvs);
  if (optional[3].layout) gather(*optional[3].layout, mesh.uvs1);
  if (color) {
    mesh.colors.assign(kept.size(), glm::vec4(1.0f));  // a VEC3 leaves alpha at 1
    for (std::size_t i = 0; i < kept.size(); ++i) readFloats(*color, kept[i], &mesh.colors[i][0]);
    checkVertexColors(mesh, where);
  }
  return mesh;
}

std::vector<std::uint32_t> GltfDocument::keepUsed(std::vector<std::uint32_t>& indices,
                                                  std::size_t vertices) {
  std::vector<std::uint32_t> kept;
  if (vertices <= 2 * indices.size() + 1024) {
    constexpr std::uint32_t unused = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> remap(vertices, unused);
    for (std::uint32_t i : indices) remap[i] = 0;
    for (std::size_t v = 0; v < vertices; ++v)
      if (remap[v] != unused) {
        remap[v] = static_cast<std::uint32_t>(kept.size());
        kept.push_back(static_cast<std::uint32_t>(v));
      }
    for (std::uint32_t& i : indices) i = remap[i];
  } else {
    kept = indices;
    std::sort(kept.begin(), kept.end());
    kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
    for (std::uint32_t& i : indices)
      i = static_cast<std::uint32_t>(std::lower_bound(kept.begin(), kept.end(), i) - kept.begin());
  }
  return kept;
}

void GltfDocument::checkVertexColors(const Mesh& mesh, const std::string& where) const {
  for (const glm::vec4& c : mesh.colors)
    for (int k = 0; k < 4; ++k)
      if (!(c[k] >= 0.0f) || !std::isfinite(c[k]))
        error(fmt::format("{}: COLOR_0 holds {}, not a color (finite, at least 0)", where, c[k]));
}

void GltfDocument::checkFinite(const Mesh& mesh, int m, std::size_t p, int node) const {
  for (const glm::vec3& v : mesh.positions)
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      error(fmt::format("{} (node {}): a vertex lies at a non-finite position",
                        primitiveLabel(m, p), node));
}

}  // namespace ibl::gltf
