// Peak memory of `ibl render` on a large glTF, as a whole process: a synthetic model (a wavy
// grid mesh with positions, normals and UVs, placed by several nodes, and 2048^2 textures)
// written as a GLB, then rendered by the CLI. Prints the process's peak resident memory beside
// what the geometry and the textures themselves take (the renderer's own data: 32 bytes per
// vertex, 12 per triangle, 4 per texel).
//   ibl_memory [--grid N] [--nodes K] [--textures T]   (default 700, 5, 5: 4.9 M triangles)
#include <sys/resource.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "ibl/core/image.hpp"
#include "ibl/io/image_io.hpp"

namespace {

namespace fs = std::filesystem;

template <typename T>
void append(std::vector<std::uint8_t>& out, const T& v) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof(T));
}

// A GLB with one N x N vertex grid mesh, placed by `nodes` nodes side by side, and `textures`
// distinct noisy 2048^2 PNG textures, each on a material of its own (one primitive per texture).
void writeModel(const fs::path& path, int n, int nodes, int textures) {
  std::vector<std::uint8_t> bin;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float x = 2.0f * i / (n - 1) - 1.0f, y = 2.0f * j / (n - 1) - 1.0f;
      for (float c : {x, y, 0.1f * std::sin(6.0f * x) * std::cos(6.0f * y)}) append(bin, c);
    }
  const std::size_t normalsAt = bin.size();
  for (int k = 0; k < n * n; ++k)
    for (float c : {0.0f, 0.0f, 1.0f}) append(bin, c);
  const std::size_t uvsAt = bin.size();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      for (float c : {static_cast<float>(i) / (n - 1), static_cast<float>(j) / (n - 1)})
        append(bin, c);
  const std::size_t indicesAt = bin.size();
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const std::uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      for (std::uint32_t v : {a, b, d, a, d, c}) append(bin, v);
    }
  const std::size_t indexCount = (bin.size() - indicesAt) / 4;
  nlohmann::json j = {{"asset", {{"version", "2.0"}}}, {"scene", 0}};
  nlohmann::json bufferViews = {
      {{"buffer", 0}, {"byteOffset", 0}, {"byteLength", normalsAt}},
      {{"buffer", 0}, {"byteOffset", normalsAt}, {"byteLength", uvsAt - normalsAt}},
      {{"buffer", 0}, {"byteOffset", uvsAt}, {"byteLength", indicesAt - uvsAt}},
      {{"buffer", 0}, {"byteOffset", indicesAt}, {"byteLength", bin.size() - indicesAt}}};
  nlohmann::json images = nlohmann::json::array(), materials = nlohmann::json::array(),
                 texturesJson = nlohmann::json::array(), primitives = nlohmann::json::array();
  std::uint32_t seed = 1;
  for (int t = 0; t < std::max(textures, 1); ++t) {
    nlohmann::json material = {{"pbrMetallicRoughness", {{"roughnessFactor", 0.5}}}};
    if (t < textures) {
      ibl::Image img(2048, 2048);
      for (glm::vec3& p : img.pixels) {
        seed = seed * 1664525u + 1013904223u;
        p = glm::vec3((seed >> 8) % 256, (seed >> 16) % 256, seed >> 24) / 255.0f;
      }
      while (bin.size() % 4) bin.push_back(0);
      const std::vector<std::uint8_t> png = ibl::encodePng(img);
      bufferViews.push_back(
          {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", png.size()}});
      bin.insert(bin.end(), png.begin(), png.end());
      images.push_back({{"bufferView", bufferViews.size() - 1}, {"mimeType", "image/png"}});
      texturesJson.push_back({{"source", t}});
      material["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", t}};
    }
    materials.push_back(material);
    // Each primitive draws a slice of the triangles (with the texture's material).
    const std::size_t slice = indexCount / 3 / std::max(textures, 1) * 3;
    primitives.push_back({{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
                          {"indices", 3 + t},
                          {"material", t}});
    j["accessors"].push_back({{"bufferView", 3},
                              {"byteOffset", t * slice * 4},
                              {"componentType", 5125},
                              {"count", slice},
                              {"type", "SCALAR"}});
  }
  const nlohmann::json vertexAccessors = {
      {{"bufferView", 0},
       {"componentType", 5126},
       {"count", n * n},
       {"type", "VEC3"},
       {"min", {-1.0, -1.0, -0.1}},
       {"max", {1.0, 1.0, 0.1}}},
      {{"bufferView", 1}, {"componentType", 5126}, {"count", n * n}, {"type", "VEC3"}},
      {{"bufferView", 2}, {"componentType", 5126}, {"count", n * n}, {"type", "VEC2"}}};
  j["accessors"].insert(j["accessors"].begin(), vertexAccessors.begin(), vertexAccessors.end());
  while (bin.size() % 4) bin.push_back(0);
  j["buffers"] = {{{"byteLength", bin.size()}}};
  j["bufferViews"] = bufferViews;
  j["meshes"] = {{{"primitives", primitives}}};
  j["materials"] = materials;
  if (textures > 0) {
    j["images"] = images;
    j["textures"] = texturesJson;
  }
  nlohmann::json nodeList = nlohmann::json::array(), sceneNodes = nlohmann::json::array();
  for (int k = 0; k < nodes; ++k) {
    nodeList.push_back({{"mesh", 0}, {"translation", {2.2 * k - 1.1 * (nodes - 1), 0.0, 0.0}}});
    sceneNodes.push_back(k);
  }
  j["nodes"] = nodeList;
  j["scenes"] = {{{"nodes", sceneNodes}}};
  std::string json = j.dump();
  while (json.size() % 4) json += ' ';
  std::vector<std::uint8_t> glb;
  for (std::uint32_t v :
       {0x46546C67u, 2u, static_cast<std::uint32_t>(28 + json.size() + bin.size()),
        static_cast<std::uint32_t>(json.size()), 0x4E4F534Au})
    append(glb, v);
  glb.insert(glb.end(), json.begin(), json.end());
  for (std::uint32_t v : {static_cast<std::uint32_t>(bin.size()), 0x004E4942u}) append(glb, v);
  glb.insert(glb.end(), bin.begin(), bin.end());
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(glb.data()), static_cast<std::streamsize>(glb.size()));
}

}  // namespace

int main(int argc, char** argv) {
  int grid = 700, nodes = 5, textures = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    int& target = a == "--grid" ? grid : a == "--nodes" ? nodes : textures;
    target = std::atoi(argv[i + 1]);
  }
  const fs::path dir = fs::temp_directory_path() / fmt::format("ibl_memory_{}", ::getpid());
  fs::create_directories(dir);
  const fs::path model = dir / "model.glb";
  writeModel(model, grid, nodes, textures);
  const double vertices = static_cast<double>(grid) * grid * nodes;
  const double triangles = 2.0 * (grid - 1) * (grid - 1) * nodes;
  const double geometryMb = (32.0 * vertices + 12.0 * triangles) / 1e6;
  const double textureMb = 4.0 * 2048 * 2048 * textures / 1e6;
  const std::string command =
      fmt::format("{} render {} -o {} --size 256x256 --spp 1 >/dev/null 2>&1", IBL_CLI,
                  model.string(), (dir / "out.png").string());
  const int status = std::system(command.c_str());
  rusage u{};
  ::getrusage(RUSAGE_CHILDREN, &u);
  fs::remove_all(dir);
  if (status != 0) {
    fmt::print(stderr, "ibl_memory: `ibl render` failed\n");
    return 1;
  }
  fmt::print(
      "{:.2f} M triangles ({} nodes), {} textures of 2048^2: geometry {:.0f} MB + textures {:.0f} "
      "MB = {:.0f} MB; `ibl render` peak {:.0f} MB ({:.2f}x)\n",
      triangles / 1e6, nodes, textures, geometryMb, textureMb, geometryMb + textureMb,
      u.ru_maxrss / 1e3, u.ru_maxrss / 1e3 / (geometryMb + textureMb));
}
