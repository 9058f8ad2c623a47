// Compressed geometry: EXT_meshopt_compression's buffer views (meshoptimizer's codecs and
// filters) and KHR_draco_mesh_compression's streams (Draco's decoder), each bounded before it
// is decoded.
#include <algorithm>
#include <cstring>
#include <map>
#include <memory>

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/core/varint_decoding.h>
#include <draco/metadata/metadata_decoder.h>
#include <fmt/format.h>
#include <meshoptimizer.h>

#include "document.hpp"

namespace ibl::gltf {

// Decodes the views hideMeshoptFallbacks listed (EXT_meshopt_compression: the vertex and index
// codecs of meshoptimizer, then the view's filter) into buffers of their own. The codecs cannot
// expand data more than 64 times (the vertex codec's densest block: 2 header bits per 16 bytes),
// and compressed views may not overlap (views of the same bytes and parameters share one
// decoding): the decoded bytes are at most 64 times the file's.
void decodeMeshoptViews(tinygltf::Model& model, const std::vector<MeshoptView>& views,
                        const std::string& path) {
  DisjointRanges compressed;
  std::map<std::string, int> decodedBuffers;  // by bytes and parameters: the decoded buffer
  for (const MeshoptView& v : views) {
    const auto bad = [&](const std::string& what) {
      fail(path, fmt::format("buffer view {}: EXT_meshopt_compression {}", v.index, what));
    };
    const tinygltf::BufferView& bv = model.bufferViews.at(static_cast<std::size_t>(v.index));
    if (!inRange(bv.buffer, model.buffers.size()))
      bad(outOfRange("buffer", bv.buffer, model.buffers.size()));
    const std::size_t bufferSize = model.buffers[static_cast<std::size_t>(bv.buffer)].data.size();
    if (bv.byteOffset > bufferSize || bv.byteLength > bufferSize - bv.byteOffset)
      bad("data past the end of its buffer");
    if (!compressed.add(bv.buffer, bv.byteOffset, bv.byteOffset + bv.byteLength))
      bad("data overlaps another compressed view's");
    const std::string key =
        fmt::format("{} {} {} {} {} {} {} {}", bv.buffer, bv.byteOffset, bv.byteLength, v.count,
                    v.stride, v.byteLength, v.mode, v.filter);
    if (const auto same = decodedBuffers.find(key); same != decodedBuffers.end()) {
      tinygltf::BufferView& out = model.bufferViews[static_cast<std::size_t>(v.index)];
      out.buffer = same->second;
      out.byteOffset = 0;
      out.byteLength = v.byteLength;
      continue;
    }
    const bool attributes = v.mode == "ATTRIBUTES";
    if (!attributes && v.mode != "TRIANGLES" && v.mode != "INDICES") bad("mode " + v.mode);
    if (attributes ? v.stride == 0 || v.stride % 4 || v.stride > 256
                   : v.stride != 2 && v.stride != 4)
      bad(fmt::format("byteStride {} for mode {}", v.stride, v.mode));
    if (v.mode == "TRIANGLES" && v.count % 3) bad("triangle index count not a multiple of 3");
    if (v.count > (std::size_t{1} << 32) / v.stride || v.count * v.stride > v.byteLength ||
        v.byteLength > (v.count * v.stride + 3) / 4 * 4)
      bad(fmt::format("count {} of {} bytes for a view of {} bytes", v.count, v.stride,
                      v.byteLength));
    if (v.byteLength > 64 * u64{bv.byteLength})
      bad(fmt::format("{} bytes cannot decode to {}: corrupt", bv.byteLength, v.byteLength));
    const unsigned char* src =
        model.buffers[static_cast<std::size_t>(bv.buffer)].data.data() + bv.byteOffset;
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
    decodedBuffers[key] = out.buffer;
    model.buffers.push_back(std::move(decoded));
  }
}

// The number of triangles a Draco mesh stream's header declares. The decoder allocates for them
// before it reads them, however short the stream (the edgebreaker's corner table: 24 bytes a
// triangle), so they are counted against the limit first. Read as the decoder reads it (Draco's
// own buffer, varints and metadata decoder); 0 for a header the decoder refuses without
// allocating (not a mesh, an unknown version or method).
u64 dracoDeclaredFaces(std::span<const std::uint8_t> bytes) {
  draco::DecoderBuffer b;
  b.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  char magic[5];
  std::uint8_t major = 0, minor = 0, type = 0, method = 0;
  std::uint16_t flags = 0;
  if (!b.Decode(magic, 5) || std::memcmp(magic, "DRACO", 5) != 0 || !b.Decode(&major) ||
      !b.Decode(&minor) || !b.Decode(&type) || !b.Decode(&method) || !b.Decode(&flags) ||
      type != draco::TRIANGULAR_MESH)
    return 0;
  const auto version = static_cast<std::uint16_t>((major << 8) | minor);
  b.set_bitstream_version(version);
  if (flags & METADATA_FLAG_MASK) {
    draco::GeometryMetadata metadata;
    if (!draco::MetadataDecoder().DecodeGeometryMetadata(&b, &metadata)) return 0;
  }
  // Before bitstream 2.0 the counts are 32-bit words, varints since (the sequential method's since
  // 2.2).
  const auto count = [&](bool varint, std::uint32_t& v) {
    return varint ? draco::DecodeVarint(&v, &b) : b.Decode(&v);
  };
  std::uint32_t faces = 0, skipped = 0;
  if (method == draco::MESH_EDGEBREAKER_ENCODING) {
    std::uint8_t traversal = 0;
    if (!b.Decode(&traversal)) return 0;
    if (version < 0x0202 && !count(version >= 0x0200, skipped)) return 0;  // new vertices
    if (!count(version >= 0x0200, skipped) || !count(version >= 0x0200, faces)) return 0;
  } else if (method == draco::MESH_SEQUENTIAL_ENCODING) {
    if (!count(version >= 0x0202, faces)) return 0;
  }
  return faces;
}

std::span<const std::uint8_t> GltfDocument::dracoBytes(int m, std::size_t p) const {
  const tinygltf::Primitive& prim = model_.meshes[static_cast<std::size_t>(m)].primitives[p];
  const tinygltf::Value& ext = prim.extensions.at("KHR_draco_mesh_compression");
  const int view = *extensionIndex(ext, "bufferView", path_, primitiveLabel(m, p));
  const tinygltf::BufferView& bv = model_.bufferViews[static_cast<std::size_t>(view)];
  return {model_.buffers[static_cast<std::size_t>(bv.buffer)].data.data() + bv.byteOffset,
          bv.byteLength};
}

Mesh GltfDocument::readDracoPrimitive(int m, std::size_t p) const {
  const tinygltf::Primitive& prim = model_.meshes[static_cast<std::size_t>(m)].primitives[p];
  const std::string where = primitiveLabel(m, p) + ": KHR_draco_mesh_compression";
  const tinygltf::Value& ext = prim.extensions.at("KHR_draco_mesh_compression");
  const std::span<const std::uint8_t> bytes = dracoBytes(m, p);
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok())
    error(fmt::format("{}: decoding failed: {}", where, decoded.status().error_msg_string()));
  const std::unique_ptr<draco::Mesh> dm = std::move(decoded).value();
  const std::size_t points = dm->num_points();
  Mesh mesh;
  mesh.indices.reserve(static_cast<std::size_t>(dm->num_faces()) * 3);
  for (draco::FaceIndex f(0); f < dm->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = dm->face(f)[k].value();
      if (v >= points) error(fmt::format("{}: a face names point {} of {}", where, v, points));
      mesh.indices.push_back(v);
    }
  const std::vector<std::uint32_t> kept = keepUsed(mesh.indices, points);
  const tinygltf::Value& attributes = ext.Get("attributes");
  // n components of attribute `name` into `out` (a VEC3 color's alpha stays 1).
  const auto read = [&](const char* name, int n, auto& out) {
    if (!attributes.Has(name)) return;
    const draco::PointAttribute* att = dm->GetAttributeByUniqueId(static_cast<std::uint32_t>(
        *extensionIndex(attributes, name, path_, where + " attributes")));
    if (!att) error(fmt::format("{}: the stream has no {} attribute", where, name));
    if (n == 0) n = std::clamp(static_cast<int>(att->num_components()), 3, 4);
    out.resize(kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i) {
      float v[4] = {0, 0, 0, 1};
      att->ConvertValue<float>(att->mapped_index(draco::PointIndex(kept[i])),
                               static_cast<std::int8_t>(n), v);
      for (int c = 0; c < static_cast<int>(out[i].length()); ++c) out[i][c] = v[c];
    }
  };
  if (!attributes.Has("POSITION")) error(where + " has no POSITION");
  read("POSITION", 3, mesh.positions);
  read("NORMAL", 3, mesh.normals);
  read("TEXCOORD_0", 2, mesh.uvs);
  read("TANGENT", 4, mesh.tangents);
  read("TEXCOORD_1", 2, mesh.uvs1);
  read("COLOR_0", 0, mesh.colors);  // VEC3 or VEC4, as the stream holds it
  if (!mesh.colors.empty()) checkVertexColors(mesh, where);
  return mesh;
}

}  // namespace ibl::gltf
