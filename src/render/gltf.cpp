// glTF 2.0 loading: tinygltf parses, stb_image decodes the images, Draco decodes compressed
// primitives, meshoptimizer decodes compressed buffer views; this file turns the model into a
// Scene, step by step (readGltfModel, readTextures, readMaterials, then NodeVisitor: readPrimitive,
// checkMesh, placeInWorld).
#include "ibl/render/gltf.hpp"

#include <cstring>
#include <functional>
#include <limits>

#include <draco/compression/decode.h>
#include <fmt/format.h>
#include <meshoptimizer.h>
#include <stb_image.h>
#include <tiny_gltf.h>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"

namespace ibl {

namespace {

// Images through stb_image (8-bit RGBA), whatever tinygltf was built with.
bool loadImageWithStb(tinygltf::Image* image, const int index, std::string* err, std::string*, int,
                      int, const unsigned char* bytes, int size, void*) {
  int w = 0, h = 0, comp = 0;
  unsigned char* px = stbi_load_from_memory(bytes, size, &w, &h, &comp, 4);
  if (!px) {
    if (err) *err += fmt::format("image {}: {}\n", index, stbi_failure_reason());
    return false;
  }
  image->width = w;
  image->height = h;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image.assign(px, px + static_cast<std::size_t>(w) * h * 4);
  stbi_image_free(px);
  return true;
}

std::string firstLine(const std::string& s) {
  const auto nl = s.find('\n');
  return nl == std::string::npos ? s : s.substr(0, nl);
}

class GltfReader {
 public:
  GltfReader(const tinygltf::Model& model, const std::string& path) : model_(model), path_(path) {}

  // Reads accessor `index` as `n`-component floats (normalized integers scaled to [0, 1]).
  std::vector<float> floats(int index, int n) const {
    if (index < 0 || index >= static_cast<int>(model_.accessors.size()))
      fail(path_, "accessor index out of range");
    const tinygltf::Accessor& a = model_.accessors[index];
    const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    if (components != n)
      fail(path_, fmt::format("accessor {} has {} components, expected {}", index, components, n));
    std::vector<float> out(a.count * n, 0.0f);
    if (a.bufferView >= 0) {  // else zeros, to which a sparse accessor's values are applied
      const auto [data, stride] = view(a, n);
      for (std::size_t i = 0; i < a.count; ++i)
        for (int c = 0; c < n; ++c)
          out[i * n + c] = component(data + i * stride, a.componentType, c, a.normalized);
    }
    if (a.sparse.isSparse) applySparse(a, n, index, out);
    return out;
  }

  std::vector<std::uint32_t> indices(int index) const {
    return indicesOf(model_.accessors.at(index));
  }

  std::vector<std::uint32_t> indicesOf(const tinygltf::Accessor& a) const {
    const auto [data, stride] = view(a, 1);
    std::vector<std::uint32_t> out(a.count);
    for (std::size_t i = 0; i < a.count; ++i) {
      const unsigned char* p = data + i * stride;
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          out[i] = *p;
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          std::uint16_t v;
          std::memcpy(&v, p, 2);
          out[i] = v;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
          std::memcpy(&out[i], p, 4);
          break;
        default:
          fail(path_, "index accessor of a non-integer type");
      }
    }
    return out;
  }

  std::pair<const unsigned char*, std::size_t> bufferViewBytes(int index) const {
    const tinygltf::BufferView& bv = model_.bufferViews.at(index);
    const tinygltf::Buffer& b = model_.buffers.at(bv.buffer);
    if (bv.byteOffset + bv.byteLength > b.data.size())
      fail(path_, "buffer view past the end of its buffer");
    return {b.data.data() + bv.byteOffset, bv.byteLength};
  }

 private:
  // A sparse accessor (glTF 2.0, 3.6.2.3): `count` indices into the accessor, and the values
  // that replace the elements there.
  void applySparse(const tinygltf::Accessor& a, int n, int index, std::vector<float>& out) const {
    const auto& s = a.sparse;
    if (s.count < 0 || static_cast<std::size_t>(s.count) > a.count)
      fail(path_, fmt::format("sparse accessor {} has {} values for {} elements", index, s.count,
                              a.count));
    tinygltf::Accessor indexAccessor;
    indexAccessor.bufferView = s.indices.bufferView;
    indexAccessor.byteOffset = static_cast<std::size_t>(s.indices.byteOffset);
    indexAccessor.componentType = s.indices.componentType;
    indexAccessor.count = static_cast<std::size_t>(s.count);
    indexAccessor.type = TINYGLTF_TYPE_SCALAR;
    tinygltf::Accessor valueAccessor = a;
    valueAccessor.bufferView = s.values.bufferView;
    valueAccessor.byteOffset = static_cast<std::size_t>(s.values.byteOffset);
    valueAccessor.count = static_cast<std::size_t>(s.count);
    if (indexAccessor.bufferView < 0 || valueAccessor.bufferView < 0 ||
        indexAccessor.bufferView >= static_cast<int>(model_.bufferViews.size()) ||
        valueAccessor.bufferView >= static_cast<int>(model_.bufferViews.size()))
      fail(path_, fmt::format("sparse accessor {} has no indices or values", index));
    const std::vector<std::uint32_t> at = indicesOf(indexAccessor);
    const auto [data, stride] = view(valueAccessor, n);
    for (std::size_t k = 0; k < at.size(); ++k) {
      if (at[k] >= a.count)
        fail(path_,
             fmt::format("sparse accessor {} replaces element {} of {}", index, at[k], a.count));
      for (int c = 0; c < n; ++c)
        out[at[k] * n + c] = component(data + k * stride, a.componentType, c, a.normalized);
    }
  }

  std::pair<const unsigned char*, std::size_t> view(const tinygltf::Accessor& a, int n) const {
    const tinygltf::BufferView& bv = model_.bufferViews.at(a.bufferView);
    const tinygltf::Buffer& b = model_.buffers.at(bv.buffer);
    const std::size_t size = static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(
                                 static_cast<std::uint32_t>(a.componentType))) *
                             n;
    const std::size_t stride = bv.byteStride ? bv.byteStride : size;
    const std::size_t start = bv.byteOffset + a.byteOffset;
    if (a.count > 0 && (start + (a.count - 1) * stride + size > b.data.size() || size == 0))
      fail(path_, "accessor reads past the end of its buffer");
    return {b.data.data() + start, stride};
  }

  float component(const unsigned char* p, int type, int c, bool normalized) const {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p + 4 * c, 4);
        return v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return normalized ? p[c] / 255.0f : p[c];
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const auto v = static_cast<signed char>(p[c]);
        return normalized ? std::max(v / 127.0f, -1.0f) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p + 2 * c, 2);
        return normalized ? v / 65535.0f : v;
      }
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t v;
        std::memcpy(&v, p + 2 * c, 2);
        return normalized ? std::max(v / 32767.0f, -1.0f) : v;
      }
      default:
        fail(path_, "unsupported accessor component type");
    }
  }

  const tinygltf::Model& model_;
  const std::string& path_;
};

glm::mat4 nodeTransform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(node.matrix[i]);
    return m;
  }
  glm::mat4 t(1.0f), r(1.0f), s(1.0f);
  if (node.translation.size() == 3)
    t[3] =
        glm::vec4(static_cast<float>(node.translation[0]), static_cast<float>(node.translation[1]),
                  static_cast<float>(node.translation[2]), 1.0f);
  if (node.rotation.size() == 4)
    r = glm::mat4_cast(
        glm::quat(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                  static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2])));
  if (node.scale.size() == 3)
    s = glm::scale(glm::mat4(1.0f),
                   glm::vec3(static_cast<float>(node.scale[0]), static_cast<float>(node.scale[1]),
                             static_cast<float>(node.scale[2])));
  return t * r * s;
}

// Area-weighted vertex normals.
std::vector<glm::vec3> generateNormals(const Mesh& m) {
  std::vector<glm::vec3> n(m.positions.size(), glm::vec3(0.0f));
  for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
    const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                    c = m.positions[m.indices[i + 2]];
    const glm::vec3 face = glm::cross(b - a, c - a);
    for (int k = 0; k < 3; ++k) n[m.indices[i + k]] += face;
  }
  for (auto& v : n) v = glm::length(v) > 0.0f ? glm::normalize(v) : glm::vec3(0, 0, 1);
  return n;
}

// Tangents from UV derivatives per triangle, accumulated and orthogonalized per vertex
// (Lengyel 2001), handedness in w, from the UV set `uvs` (the normal texture's).
std::vector<glm::vec4> generateTangents(const Mesh& m, const std::vector<glm::vec2>& uvs) {
  std::vector<glm::vec3> tan(m.positions.size(), glm::vec3(0.0f)),
      bit(m.positions.size(), glm::vec3(0.0f));
  for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
    const std::uint32_t i0 = m.indices[i], i1 = m.indices[i + 1], i2 = m.indices[i + 2];
    const glm::vec3 e1 = m.positions[i1] - m.positions[i0], e2 = m.positions[i2] - m.positions[i0];
    const glm::vec2 d1 = uvs[i1] - uvs[i0], d2 = uvs[i2] - uvs[i0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-20f) continue;
    const float r = 1.0f / det;
    const glm::vec3 t = (e1 * d2.y - e2 * d1.y) * r, b = (e2 * d1.x - e1 * d2.x) * r;
    for (std::uint32_t k : {i0, i1, i2}) {
      tan[k] += t;
      bit[k] += b;
    }
  }
  std::vector<glm::vec4> out(m.positions.size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    const glm::vec3 n = m.normals[k];
    glm::vec3 t = tan[k] - n * glm::dot(n, tan[k]);
    if (glm::length(t) < 1e-12f)
      t = std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0))
                               : glm::cross(n, glm::vec3(0, 1, 0));
    t = glm::normalize(t);
    out[k] = glm::vec4(t, glm::dot(glm::cross(n, t), bit[k]) < 0.0f ? -1.0f : 1.0f);
  }
  return out;
}

// A KHR_draco_mesh_compression primitive: attributes and triangles from the Draco stream.
void decodeDracoPrimitive(const GltfReader& reader, const tinygltf::Value& ext, Mesh& mesh,
                          const std::string& path) {
  const auto [bytes, size] = reader.bufferViewBytes(ext.Get("bufferView").GetNumberAsInt());
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes), size);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok())
    fail(path, fmt::format("Draco decoding failed: {}", decoded.status().error_msg_string()));
  const std::unique_ptr<draco::Mesh> dm = std::move(decoded).value();
  const tinygltf::Value& attributes = ext.Get("attributes");
  const auto read = [&](const char* name, int n, auto& out) {
    if (!attributes.Has(name)) return;
    const draco::PointAttribute* att = dm->GetAttributeByUniqueId(
        static_cast<std::uint32_t>(attributes.Get(name).GetNumberAsInt()));
    if (!att) fail(path, fmt::format("Draco stream has no {} attribute", name));
    out.resize(dm->num_points());
    for (draco::PointIndex i(0); i < dm->num_points(); ++i) {
      float v[4] = {0, 0, 0, 0};
      att->ConvertValue<float>(att->mapped_index(i), static_cast<std::int8_t>(n), v);
      for (int c = 0; c < n; ++c) out[i.value()][c] = v[c];
    }
  };
  read("POSITION", 3, mesh.positions);
  read("NORMAL", 3, mesh.normals);
  read("TEXCOORD_0", 2, mesh.uvs);
  read("TANGENT", 4, mesh.tangents);
  read("TEXCOORD_1", 2, mesh.uvs1);
  for (draco::FaceIndex f(0); f < dm->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) mesh.indices.push_back(dm->face(f)[k].value());
}

// Debian's tinygltf is built without Draco and rejects the accessors of Draco primitives (they
// have no buffer view). Those accessors are not needed (the Draco stream has the data), so
// drop them from such primitives before tinygltf sees the JSON. Returns whether it changed any.
bool hideDracoAccessors(nlohmann::json& gltf) {
  bool changed = false;
  if (!gltf.contains("meshes")) return changed;
  for (auto& mesh : gltf["meshes"]) {
    if (!mesh.contains("primitives")) continue;
    for (auto& prim : mesh["primitives"]) {
      if (!prim.contains("extensions") ||
          !prim["extensions"].contains("KHR_draco_mesh_compression"))
        continue;
      prim.erase("indices");
      prim["attributes"] = nlohmann::json::object();
      changed = true;
    }
  }
  return changed;
}

// A buffer view compressed with EXT_meshopt_compression: after hideMeshoptFallbacks, tinygltf
// sees it as the compressed bytes; decodeMeshoptViews turns it back into `count` elements of
// `stride` bytes.
struct MeshoptView {
  int index = 0;
  std::size_t count = 0, stride = 0, byteLength = 0;  // byteLength: of the decoded view
  std::string mode, filter;
};

// EXT_meshopt_compression stores each compressed view's bytes elsewhere and may give the view's
// own buffer no data at all (a "fallback" buffer: no uri, or a GLB buffer that is not the BIN
// chunk), which tinygltf rejects. Point each compressed view at its compressed bytes, give
// fallback buffers a 4-byte placeholder, and list the views to decode once tinygltf is done.
// Returns whether it changed anything.
bool hideMeshoptFallbacks(nlohmann::json& gltf, const std::string& path,
                          std::vector<MeshoptView>& views) {
  if (!gltf.contains("bufferViews")) return false;
  const auto extensionOf = [](const nlohmann::json& o) -> const nlohmann::json* {
    if (!o.is_object() || !o.contains("extensions")) return nullptr;
    const auto& e = o["extensions"];
    return e.is_object() && e.contains("EXT_meshopt_compression") ? &e["EXT_meshopt_compression"]
                                                                  : nullptr;
  };
  std::vector<bool> fallback;
  if (gltf.contains("buffers"))
    for (const auto& b : gltf["buffers"]) {
      const nlohmann::json* e = extensionOf(b);
      fallback.push_back(e && e->value("fallback", false));
    }
  auto& bufferViews = gltf["bufferViews"];
  for (std::size_t i = 0; i < bufferViews.size(); ++i) {
    auto& bv = bufferViews[i];
    const nlohmann::json* e = extensionOf(bv);
    if (!e) {
      const int buffer = bv.value("buffer", -1);
      if (buffer >= 0 && static_cast<std::size_t>(buffer) < fallback.size() && fallback[buffer])
        fail(path,
             fmt::format("buffer view {} reads fallback buffer {}, which has no data", i, buffer));
      continue;
    }
    try {
      MeshoptView v;
      v.index = static_cast<int>(i);
      v.count = e->at("count").get<std::size_t>();
      v.stride = e->at("byteStride").get<std::size_t>();
      v.mode = e->at("mode").get<std::string>();
      v.filter = e->value("filter", std::string("NONE"));
      v.byteLength = bv.at("byteLength").get<std::size_t>();
      bv["buffer"] = e->at("buffer");
      bv["byteOffset"] = e->value("byteOffset", 0);
      bv["byteLength"] = e->at("byteLength");
      bv["extensions"].erase("EXT_meshopt_compression");
      views.push_back(std::move(v));
    } catch (const nlohmann::json::exception&) {
      fail(path, fmt::format("buffer view {}: EXT_meshopt_compression without a valid buffer, "
                             "byteLength, byteStride, count or mode",
                             i));
    }
  }
  bool changed = !views.empty();
  for (std::size_t b = 0; b < fallback.size(); ++b)
    if (fallback[b]) {
      gltf["buffers"][b] = {{"byteLength", 4},
                            {"uri", "data:application/octet-stream;base64,AAAAAA=="}};
      changed = true;
    }
  return changed;
}

// Decodes the views hideMeshoptFallbacks listed (EXT_meshopt_compression: the vertex and index
// codecs of meshoptimizer, then the view's filter) into buffers of their own.
void decodeMeshoptViews(tinygltf::Model& model, const std::vector<MeshoptView>& views,
                        const std::string& path) {
  for (const MeshoptView& v : views) {
    const auto bad = [&](const std::string& what) {
      fail(path, fmt::format("buffer view {}: EXT_meshopt_compression {}", v.index, what));
    };
    const tinygltf::BufferView& bv = model.bufferViews.at(static_cast<std::size_t>(v.index));
    if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model.buffers.size() ||
        bv.byteOffset + bv.byteLength > model.buffers[bv.buffer].data.size())
      bad("data past the end of its buffer");
    const bool attributes = v.mode == "ATTRIBUTES";
    if (!attributes && v.mode != "TRIANGLES" && v.mode != "INDICES") bad("mode " + v.mode);
    if (attributes ? v.stride == 0 || v.stride % 4 || v.stride > 256
                   : v.stride != 2 && v.stride != 4)
      bad(fmt::format("byteStride {} for mode {}", v.stride, v.mode));
    if (v.mode == "TRIANGLES" && v.count % 3) bad("triangle index count not a multiple of 3");
    if (v.count > (std::size_t{1} << 32) / v.stride || v.count * v.stride > v.byteLength)
      bad(fmt::format("count {} of {} bytes for a view of {} bytes", v.count, v.stride,
                      v.byteLength));
    const unsigned char* src = model.buffers[bv.buffer].data.data() + bv.byteOffset;
    tinygltf::Buffer decoded;
    decoded.data.resize(v.byteLength);
    const int status =
        attributes
            ? meshopt_decodeVertexBuffer(decoded.data.data(), v.count, v.stride, src, bv.byteLength)
        : v.mode == "TRIANGLES"
            ? meshopt_decodeIndexBuffer(decoded.data.data(), v.count, v.stride, src, bv.byteLength)
            : meshopt_decodeIndexSequence(decoded.data.data(), v.count, v.stride, src,
                                          bv.byteLength);
    if (status != 0) bad("data is corrupt");
    if (v.filter == "OCTAHEDRAL") {
      if (!attributes || (v.stride != 4 && v.stride != 8)) bad("OCTAHEDRAL filter on this view");
      meshopt_decodeFilterOct(decoded.data.data(), v.count, v.stride);
    } else if (v.filter == "QUATERNION") {
      if (!attributes || v.stride != 8) bad("QUATERNION filter on this view");
      meshopt_decodeFilterQuat(decoded.data.data(), v.count, v.stride);
    } else if (v.filter == "EXPONENTIAL") {
      if (!attributes) bad("EXPONENTIAL filter on this view");
      meshopt_decodeFilterExp(decoded.data.data(), v.count, v.stride);
    } else if (v.filter != "NONE") {
      bad("filter " + v.filter);
    }
    tinygltf::BufferView& out = model.bufferViews[static_cast<std::size_t>(v.index)];
    out.buffer = static_cast<int>(model.buffers.size());
    out.byteOffset = 0;
    out.byteLength = v.byteLength;
    model.buffers.push_back(std::move(decoded));
  }
}

std::uint32_t readLe32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) |
         (static_cast<std::uint32_t>(b[at + 3]) << 24);
}
void appendLe32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

// Loads .gltf text or a .glb container from memory, with hideDracoAccessors and
// hideMeshoptFallbacks applied (whose views to decode go to `meshopt`).
bool loadGltfModel(tinygltf::TinyGLTF& loader, tinygltf::Model& model, std::string& err,
                   std::string& warn, const std::string& path, std::vector<MeshoptView>& meshopt) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  const std::string baseDir = std::filesystem::path(path).parent_path().string();
  // The JSON with hideDracoAccessors and hideMeshoptFallbacks applied; empty if unchanged.
  const auto rewrite = [&](const char* begin, const char* end) {
    try {
      nlohmann::json j = nlohmann::json::parse(begin, end);
      const bool draco = hideDracoAccessors(j);
      return hideMeshoptFallbacks(j, path, meshopt) || draco ? j.dump() : std::string();
    } catch (const nlohmann::json::exception& e) {
      fail(path,
           fmt::format("not a readable glTF 2.0 file: invalid JSON ({})", firstLine(e.what())));
    }
  };
  if (bytes.size() >= 12 && readLe32(bytes, 0) == 0x46546C67u) {  // "glTF": a GLB container
    if (bytes.size() < 20 || readLe32(bytes, 16) != 0x4E4F534Au)
      fail(path, "GLB without a JSON chunk");
    const std::uint32_t jsonLength = readLe32(bytes, 12);
    if (20ull + jsonLength > bytes.size()) fail(path, "truncated GLB");
    std::string json = rewrite(reinterpret_cast<const char*>(bytes.data() + 20),
                               reinterpret_cast<const char*>(bytes.data() + 20 + jsonLength));
    if (json.empty())  // as it is: no second copy of a large file
      return loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                         static_cast<unsigned>(bytes.size()), baseDir);
    while (json.size() % 4) json += ' ';
    std::vector<std::uint8_t> glb;
    appendLe32(glb, 0x46546C67u);
    appendLe32(glb, 2);
    appendLe32(glb, 0);  // total length, below
    appendLe32(glb, static_cast<std::uint32_t>(json.size()));
    appendLe32(glb, 0x4E4F534Au);
    glb.insert(glb.end(), json.begin(), json.end());
    glb.insert(glb.end(), bytes.begin() + 20 + jsonLength, bytes.end());  // the BIN chunk, as is
    const auto total = static_cast<std::uint32_t>(glb.size());
    for (int i = 0; i < 4; ++i) glb[8 + i] = static_cast<std::uint8_t>(total >> (8 * i));
    return loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), total, baseDir);
  }
  const auto* text = reinterpret_cast<const char*>(bytes.data());
  const std::string json = rewrite(text, text + bytes.size());
  return json.empty() ? loader.LoadASCIIFromString(&model, &err, &warn, text,
                                                   static_cast<unsigned>(bytes.size()), baseDir)
                      : loader.LoadASCIIFromString(&model, &err, &warn, json.c_str(),
                                                   static_cast<unsigned>(json.size()), baseDir);
}

// The model, parsed; required extensions we do not implement are an error.
tinygltf::Model readGltfModel(const std::string& path) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(loadImageWithStb, nullptr);
  std::string err, warn;
  std::vector<MeshoptView> meshopt;
  if (!loadGltfModel(loader, model, err, warn, path, meshopt))
    fail(path,
         fmt::format("not a readable glTF 2.0 file: {}", firstLine(err.empty() ? warn : err)));
  for (const std::string& ext : model.extensionsRequired)
    if (ext != "KHR_draco_mesh_compression" && ext != "KHR_materials_emissive_strength" &&
        ext != "KHR_materials_sheen" && ext != "KHR_mesh_quantization" &&
        ext != "EXT_meshopt_compression" && ext != "KHR_lights_punctual")
      fail(path, fmt::format("requires the extension {}, which ibl does not implement", ext));
  decodeMeshoptViews(model, meshopt, path);
  return model;
}

// A glTF sampler's wrap mode (an OpenGL enum; absent: REPEAT).
Wrap wrapOf(int mode) {
  if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return Wrap::ClampToEdge;
  if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return Wrap::MirroredRepeat;
  return Wrap::Repeat;
}

TextureSampler samplerOf(const tinygltf::Model& model, int index) {
  TextureSampler s;
  if (index < 0 || index >= static_cast<int>(model.samplers.size())) return s;
  const tinygltf::Sampler& g = model.samplers[index];
  s.wrapS = wrapOf(g.wrapS);
  s.wrapT = wrapOf(g.wrapT);
  s.nearest = g.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
  s.mipmaps = g.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST &&
              g.minFilter != TINYGLTF_TEXTURE_FILTER_LINEAR;
  return s;
}

// An image's texels as 8-bit RGBA (16-bit images keep their high byte; gray and gray-alpha
// images are spread over RGB). 8-bit RGBA, what decoders give most often, is moved, not copied.
std::shared_ptr<const std::vector<std::uint8_t>> rgba8Of(tinygltf::Image& img,
                                                         const std::string& path) {
  const std::size_t count = static_cast<std::size_t>(img.width) * img.height;
  const int channels = img.component, bytes = img.bits == 16 ? 2 : 1;
  if (img.width <= 0 || img.height <= 0 || channels < 1 || channels > 4 ||
      img.image.size() < count * channels * bytes)
    fail(path, fmt::format("image '{}' is missing, truncated or of an unsupported layout",
                           img.uri.empty() ? img.name : img.uri));
  if (channels == 4 && bytes == 1) {
    img.image.resize(count * 4);
    return std::make_shared<std::vector<std::uint8_t>>(std::move(img.image));
  }
  auto out = std::make_shared<std::vector<std::uint8_t>>(count * 4);
  for (std::size_t i = 0; i < count; ++i) {
    const auto value = [&](int c) {  // the high byte of a 16-bit value (little endian)
      return img.image[(i * channels + c) * bytes + bytes - 1];
    };
    std::uint8_t* t = out->data() + 4 * i;
    if (channels >= 3) {
      for (int c = 0; c < 3; ++c) t[c] = value(c);
    } else {
      t[0] = t[1] = t[2] = value(0);
    }
    t[3] = channels == 4 ? value(3) : channels == 2 ? value(1) : 255;
  }
  return out;
}

// The glTF textures: each an image (shared between the textures that use it) and a sampler.
// Textures whose image ibl cannot read (none, or only an extension's) are empty.
std::vector<Texture> readTextures(tinygltf::Model& model, const std::string& path) {
  std::vector<std::shared_ptr<const std::vector<std::uint8_t>>> images;
  for (std::size_t k = 0; k < model.images.size(); ++k) {
    tinygltf::Image& img = model.images[k];
    if (img.image.empty() && !img.uri.empty() && img.uri.rfind("data:", 0) != 0)
      fail(path, fmt::format("cannot read texture '{}' (image {}): missing or not an image file",
                             img.uri, k));
    images.push_back(img.image.empty() ? nullptr : rgba8Of(img, path));
  }
  std::vector<Texture> textures;
  for (const tinygltf::Texture& g : model.textures) {
    Texture t;
    if (g.source >= 0 && g.source < static_cast<int>(images.size()) && images[g.source]) {
      t.width = model.images[g.source].width;
      t.height = model.images[g.source].height;
      t.rgba = images[g.source];
    }
    t.sampler = samplerOf(model, g.sampler);
    textures.push_back(std::move(t));
  }
  return textures;
}

// The metallic-roughness materials, then a default one (gray, roughness 0.5) for primitives
// without a material; textures are indices into readTextures' list, -1 for none.
std::vector<Material> readMaterials(const tinygltf::Model& model,
                                    const std::vector<Texture>& textures) {
  const auto textureRef = [&](const auto& info) {
    TextureRef ref;
    if (info.index >= 0 && info.index < static_cast<int>(textures.size()) &&
        !textures[info.index].empty())
      ref.index = info.index;
    ref.texCoord = info.texCoord;
    return ref;
  };
  std::vector<Material> materials;
  for (const tinygltf::Material& m : model.materials) {
    Material mat;
    const auto& pbr = m.pbrMetallicRoughness;
    mat.baseColor = glm::vec3(static_cast<float>(pbr.baseColorFactor[0]),
                              static_cast<float>(pbr.baseColorFactor[1]),
                              static_cast<float>(pbr.baseColorFactor[2]));
    mat.baseColorTexture = textureRef(pbr.baseColorTexture);
    mat.baseColorAlpha = static_cast<float>(pbr.baseColorFactor[3]);
    mat.alphaMode = m.alphaMode == "MASK"    ? AlphaMode::Mask
                    : m.alphaMode == "BLEND" ? AlphaMode::Blend
                                             : AlphaMode::Opaque;
    mat.alphaCutoff = static_cast<float>(m.alphaCutoff);
    mat.metallic = static_cast<float>(pbr.metallicFactor);
    mat.roughness = static_cast<float>(pbr.roughnessFactor);
    mat.metallicRoughnessTexture = textureRef(pbr.metallicRoughnessTexture);
    mat.normalTexture = textureRef(m.normalTexture);
    mat.normalScale = static_cast<float>(m.normalTexture.scale);
    mat.occlusionTexture = textureRef(m.occlusionTexture);
    mat.occlusionStrength = static_cast<float>(m.occlusionTexture.strength);
    if (m.emissiveFactor.size() == 3)
      mat.emissive = glm::vec3(static_cast<float>(m.emissiveFactor[0]),
                               static_cast<float>(m.emissiveFactor[1]),
                               static_cast<float>(m.emissiveFactor[2]));
    mat.emissiveTexture = textureRef(m.emissiveTexture);
    // KHR_materials_emissive_strength: a scale of the emission past 1 (physical units).
    const auto strength = m.extensions.find("KHR_materials_emissive_strength");
    if (strength != m.extensions.end() && strength->second.Has("emissiveStrength"))
      mat.emissive *=
          static_cast<float>(strength->second.Get("emissiveStrength").GetNumberAsDouble());
    // KHR_materials_sheen: sheenColorFactor (default 0: no sheen), sheenRoughnessFactor
    // (default 0), and their textures (color in RGB, sRGB; roughness in A).
    const auto sheen = m.extensions.find("KHR_materials_sheen");
    if (sheen != m.extensions.end()) {
      const tinygltf::Value& x = sheen->second;
      if (x.Has("sheenColorFactor") && x.Get("sheenColorFactor").ArrayLen() == 3)
        for (int c = 0; c < 3; ++c)
          mat.sheenColor[c] = static_cast<float>(
              x.Get("sheenColorFactor").Get(static_cast<std::size_t>(c)).GetNumberAsDouble());
      if (x.Has("sheenRoughnessFactor"))
        mat.sheenRoughness = static_cast<float>(x.Get("sheenRoughnessFactor").GetNumberAsDouble());
      const auto textureOf = [&](const char* name) {
        tinygltf::TextureInfo info;
        if (x.Has(name)) {
          const tinygltf::Value& t = x.Get(name);
          if (t.Has("index")) info.index = t.Get("index").GetNumberAsInt();
          if (t.Has("texCoord")) info.texCoord = t.Get("texCoord").GetNumberAsInt();
        }
        return textureRef(info);
      };
      mat.sheenColorTexture = textureOf("sheenColorTexture");
      mat.sheenRoughnessTexture = textureOf("sheenRoughnessTexture");
    }
    materials.push_back(mat);
  }
  Material fallback;
  fallback.baseColor = glm::vec3(0.8f);
  fallback.metallic = 0.0f;
  fallback.roughness = 0.5f;
  materials.push_back(fallback);
  return materials;
}

// A node's camera, placed by the node's world transform.
CameraDescription cameraOf(const tinygltf::Camera& c, const glm::mat4& world) {
  CameraDescription d;
  d.perspective = c.type != "orthographic";
  d.yfovRadians = static_cast<float>(c.perspective.yfov);
  d.xmag = static_cast<float>(c.orthographic.xmag);
  d.world = world;
  return d;
}

// Accessor `index` as floats of `n` components, copied into a vector of glm vectors.
template <typename Vec>
std::vector<Vec> readAttribute(const GltfReader& reader, int index, int n) {
  const auto values = reader.floats(index, n);
  std::vector<Vec> out(values.size() / n);
  std::memcpy(out.data(), values.data(), out.size() * sizeof(Vec));
  return out;
}

// A triangle primitive's vertices and indices in the model's space: from the Draco stream, or
// from its accessors.
Mesh readPrimitive(const GltfReader& reader, const tinygltf::Primitive& prim,
                   const std::string& path) {
  Mesh mesh;
  const auto draco = prim.extensions.find("KHR_draco_mesh_compression");
  if (draco != prim.extensions.end()) {
    decodeDracoPrimitive(reader, draco->second, mesh, path);
    return mesh;
  }
  const auto attribute = [&](const char* name) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  if (attribute("POSITION") < 0) fail(path, "a primitive has no POSITION");
  mesh.positions = readAttribute<glm::vec3>(reader, attribute("POSITION"), 3);
  if (attribute("NORMAL") >= 0)
    mesh.normals = readAttribute<glm::vec3>(reader, attribute("NORMAL"), 3);
  if (attribute("TEXCOORD_0") >= 0)
    mesh.uvs = readAttribute<glm::vec2>(reader, attribute("TEXCOORD_0"), 2);
  if (attribute("TEXCOORD_1") >= 0)
    mesh.uvs1 = readAttribute<glm::vec2>(reader, attribute("TEXCOORD_1"), 2);
  if (attribute("TANGENT") >= 0)
    mesh.tangents = readAttribute<glm::vec4>(reader, attribute("TANGENT"), 4);
  if (prim.indices >= 0) {
    mesh.indices = reader.indices(prim.indices);
  } else {
    for (std::uint32_t i = 0; i < mesh.positions.size(); ++i) mesh.indices.push_back(i);
  }
  return mesh;
}

// Indices within range, a whole number of triangles, one value of each attribute per vertex.
void checkMesh(const Mesh& mesh, const std::string& path) {
  if (mesh.indices.size() % 3 != 0)
    fail(path, "a triangle list whose index count is not a multiple of 3");
  for (std::uint32_t i : mesh.indices)
    if (i >= mesh.positions.size()) fail(path, "a vertex index is out of range");
  if ((!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) ||
      (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()) ||
      (!mesh.uvs1.empty() && mesh.uvs1.size() != mesh.positions.size()) ||
      (!mesh.tangents.empty() && mesh.tangents.size() != mesh.positions.size()))
    fail(path, "vertex attributes of different counts");
}

// Keeps only the vertices the triangles use, in their order (exporters often share one vertex
// buffer between primitives that each draw a part of it: each would otherwise keep all of it).
void dropUnusedVertices(Mesh& mesh) {
  constexpr std::uint32_t unused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> remap(mesh.positions.size(), unused);
  for (std::uint32_t i : mesh.indices) remap[i] = 0;
  std::uint32_t kept = 0;
  for (std::uint32_t& r : remap)
    if (r != unused) r = kept++;
  if (kept == mesh.positions.size()) return;
  const auto compact = [&](auto& values) {
    if (values.empty()) return;
    for (std::size_t i = 0; i < remap.size(); ++i)
      if (remap[i] != unused) values[remap[i]] = values[i];
    values.resize(kept);
    values.shrink_to_fit();
  };
  compact(mesh.positions);
  compact(mesh.normals);
  compact(mesh.tangents);
  compact(mesh.uvs);
  compact(mesh.uvs1);
  for (std::uint32_t& i : mesh.indices) i = remap[i];
}

// Moves a mesh to world space; generates the normals it lacks, and the tangents it lacks when
// it has a normal map (normalTexture.index >= 0), from the UV set that map reads.
void placeInWorld(Mesh& mesh, const glm::mat4& world, const TextureRef& normalTexture) {
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(world)));
  for (auto& p : mesh.positions) p = glm::vec3(world * glm::vec4(p, 1.0f));
  if (mesh.normals.empty()) {
    mesh.normals = generateNormals(mesh);
  } else {
    for (auto& n : mesh.normals) n = glm::normalize(normalMatrix * n);
  }
  const std::vector<glm::vec2>& uvs = normalTexture.texCoord == 1 ? mesh.uvs1 : mesh.uvs;
  if (!uvs.empty() && normalTexture.index >= 0) {
    if (mesh.tangents.empty()) {
      mesh.tangents = generateTangents(mesh, uvs);
    } else {
      for (auto& t : mesh.tangents)
        t = glm::vec4(glm::normalize(glm::mat3(world) * glm::vec3(t)), t.w);
    }
  }
}

// Walks the node hierarchy, accumulating transforms, and adds each node's triangle primitives
// (points and lines are not surfaces) and the first camera to the scene.
class NodeVisitor {
 public:
  NodeVisitor(const tinygltf::Model& model, const std::string& path, Scene& scene)
      : model_(model), path_(path), scene_(scene), reader_(model, path) {}

  void visit(int nodeIndex, const glm::mat4& parent, int depth) {
    if (nodeIndex < 0 || nodeIndex >= static_cast<int>(model_.nodes.size()) || depth > 64)
      fail(path_, "invalid or cyclic node hierarchy");
    const tinygltf::Node& node = model_.nodes[nodeIndex];
    const glm::mat4 world = parent * nodeTransform(node);
    if (node.camera >= 0 && !scene_.camera && node.camera < static_cast<int>(model_.cameras.size()))
      scene_.camera = cameraOf(model_.cameras[node.camera], world);
    if (node.mesh >= 0) addMesh(node.mesh, world);
    addLight(node, world);
    for (int child : node.children) visit(child, world, depth + 1);
  }

 private:
  void addMesh(int meshIndex, const glm::mat4& world) {
    if (meshIndex >= static_cast<int>(model_.meshes.size())) fail(path_, "mesh index out of range");
    const int defaultMaterial = static_cast<int>(scene_.materials.size()) - 1;
    for (const tinygltf::Primitive& prim : model_.meshes[meshIndex].primitives) {
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;
      Mesh mesh = readPrimitive(reader_, prim, path_);
      mesh.material =
          prim.material >= 0 && prim.material < defaultMaterial ? prim.material : defaultMaterial;
      checkMesh(mesh, path_);
      dropUnusedVertices(mesh);
      placeInWorld(mesh, world, scene_.materials[mesh.material].normalTexture);
      if (!mesh.indices.empty()) scene_.meshes.push_back(std::move(mesh));
    }
  }

  // KHR_lights_punctual: a node's light shines down the node's -Z from its origin, in the
  // extension's units (cd for point and spot, lx for directional).
  void addLight(const tinygltf::Node& node, const glm::mat4& world) {
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end() || !ext->second.Has("light")) return;
    const tinygltf::Value& index = ext->second.Get("light");
    const int i = index.IsInt() ? index.Get<int>() : -1;
    if (i < 0 || i >= static_cast<int>(model_.lights.size()))
      fail(path_,
           fmt::format("node '{}': KHR_lights_punctual light index out of range", node.name));
    const tinygltf::Light& gl = model_.lights[static_cast<std::size_t>(i)];
    Light light;
    light.name = fmt::format("{}: KHR_lights_punctual light {} ({})", path_, i,
                             gl.name.empty() ? gl.type : gl.name);
    if (gl.type == "point") {
      light.type = LightType::Point;
    } else if (gl.type == "spot") {
      light.type = LightType::Spot;
      light.innerAngle = static_cast<float>(gl.spot.innerConeAngle);
      light.outerAngle = static_cast<float>(gl.spot.outerConeAngle);
    } else if (gl.type == "directional") {
      light.type = LightType::Sun;
    } else {
      fail(light.name, fmt::format("unknown light type '{}'", gl.type));
    }
    if (gl.color.size() == 3)
      light.color = glm::vec3(static_cast<float>(gl.color[0]), static_cast<float>(gl.color[1]),
                              static_cast<float>(gl.color[2]));
    else if (!gl.color.empty())
      fail(light.name, "color must have three components");
    light.intensity = static_cast<float>(gl.intensity);
    light.range = light.type == LightType::Sun ? 0.0f : static_cast<float>(gl.range);
    light.position = glm::vec3(world[3]);
    const glm::vec3 forward = -glm::vec3(world[2]);
    if (!(glm::length(forward) > 0.0f)) fail(light.name, "the node's transform is degenerate");
    // A directional light's direction is toward the sun, against where it shines.
    light.direction = glm::normalize(light.type == LightType::Sun ? -forward : forward);
    checkLight(light);
    scene_.lights.push_back(std::move(light));
  }

  const tinygltf::Model& model_;
  const std::string& path_;
  Scene& scene_;
  const GltfReader reader_;
};

}  // namespace

Scene loadGltf(const std::string& path) {
  tinygltf::Model model = readGltfModel(path);
  Scene scene;
  scene.textures = readTextures(model, path);
  scene.materials = readMaterials(model, scene.textures);
  NodeVisitor visitor(model, path, scene);
  const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (!model.scenes.empty() && sceneIndex < static_cast<int>(model.scenes.size())) {
    for (int n : model.scenes[sceneIndex].nodes) visitor.visit(n, glm::mat4(1.0f), 0);
  } else {
    for (int n = 0; n < static_cast<int>(model.nodes.size()); ++n)
      visitor.visit(n, glm::mat4(1.0f), 0);
  }
  if (scene.meshes.empty()) fail(path, "no triangle meshes to render");
  return scene;
}

}  // namespace ibl
