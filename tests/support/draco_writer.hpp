#pragma once
// A Draco-compressed cube (KHR_draco_mesh_compression) for the loader's tests and the fuzzers'
// seeds (fuzz/make_seeds.cpp), encoded with the Draco library.
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <vector>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "ibl/render/scene.hpp"
#include "support/gltf_writer.hpp"

namespace ibl::test {

// The COLOR_0 codes writeDracoCube gives the cube's corner p: a different color per corner.
inline std::array<std::uint8_t, 3> cubeVertexColor(glm::vec3 p) {
  return {static_cast<std::uint8_t>(p.x > 0.0f ? 250 : 10),
          static_cast<std::uint8_t>(p.y > 0.0f ? 200 : 30),
          static_cast<std::uint8_t>(p.z > 0.0f ? 128 : 64)};
}

// A cube of 8 vertices and 12 triangles, for the compressed seeds.
inline Mesh cubeMesh() {
  Mesh m;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 p(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f);
    m.positions.push_back(p);
    m.normals.push_back(glm::normalize(p));
  }
  m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
               2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  return m;
}

// The cube as a KHR_draco_mesh_compression primitive (positions, normals, UVs and, with
// `colors`, COLOR_0 as normalized unsigned bytes: cubeVertexColor) in a GLB, encoded with the
// Draco library's edgebreaker or sequential method.
inline void writeDracoCube(const std::filesystem::path& path, int method, bool colors = false) {
  const Mesh m = cubeMesh();
  const int faces = static_cast<int>(m.indices.size() / 3);
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(faces);
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int nrm = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  const int uv = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  const int rgb =
      colors ? builder.AddAttribute(draco::GeometryAttribute::COLOR, 3, draco::DT_UINT8, true) : -1;
  for (int f = 0; f < faces; ++f) {
    glm::vec3 p[3], n[3];
    glm::vec2 t[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = m.indices[static_cast<std::size_t>(3 * f + k)];
      p[k] = m.positions[v];
      n[k] = m.normals[v];
      t[k] = glm::vec2(p[k].x, p[k].y) * 0.5f + 0.5f;
    }
    builder.SetAttributeValuesForFace(pos, draco::FaceIndex(f), &p[0], &p[1], &p[2]);
    builder.SetAttributeValuesForFace(nrm, draco::FaceIndex(f), &n[0], &n[1], &n[2]);
    builder.SetAttributeValuesForFace(uv, draco::FaceIndex(f), &t[0], &t[1], &t[2]);
    if (colors) {
      std::uint8_t c[3][3];
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i) c[k][i] = cubeVertexColor(p[k])[i];
      builder.SetAttributeValuesForFace(rgb, draco::FaceIndex(f), c[0], c[1], c[2]);
    }
  }
  const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  draco::Encoder encoder;
  encoder.SetEncodingMethod(method);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
  draco::EncoderBuffer buffer;
  if (!encoder.EncodeMeshToBuffer(*mesh, &buffer).ok()) throw std::runtime_error("Draco encoder");
  const std::vector<std::uint8_t> bin(buffer.data(), buffer.data() + buffer.size());
  nlohmann::json ids = {{"POSITION", mesh->attribute(pos)->unique_id()},
                        {"NORMAL", mesh->attribute(nrm)->unique_id()},
                        {"TEXCOORD_0", mesh->attribute(uv)->unique_id()}};
  if (colors) ids["COLOR_0"] = mesh->attribute(rgb)->unique_id();
  const std::size_t points = mesh->num_points();
  nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_draco_mesh_compression"}},
      {"extensionsRequired", {"KHR_draco_mesh_compression"}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}, {"scale", {2, 2, 2}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
            {"indices", 3},
            {"extensions",
             {{"KHR_draco_mesh_compression", {{"bufferView", 0}, {"attributes", ids}}}}}}}}}}},
      {"accessors",
       {{{"componentType", 5126},
         {"count", points},
         {"type", "VEC3"},
         {"min", {-1, -1, -1}},
         {"max", {1, 1, 1}}},
        {{"componentType", 5126}, {"count", points}, {"type", "VEC3"}},
        {{"componentType", 5126}, {"count", points}, {"type", "VEC2"}},
        {{"componentType", 5125}, {"count", 3 * faces}, {"type", "SCALAR"}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", bin.size()}}}},
      {"buffers", {{{"byteLength", bin.size()}}}}};
  if (colors) {
    gltf["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 4;
    gltf["accessors"].push_back(
        {{"componentType", 5121}, {"normalized", true}, {"count", points}, {"type", "VEC3"}});
  }
  const std::vector<std::uint8_t> glb = glbOf(gltf, bin);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(glb.data()), static_cast<std::streamsize>(glb.size()));
}

}  // namespace ibl::test
