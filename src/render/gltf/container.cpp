// The container and tinygltf: a GLB's chunks checked against its length, the JSON prepared
// (json_filter.cpp) and parsed by tinygltf through ibl's own file access, the extensions the file
// requires and uses weighed against those ibl implements.
#include <cstring>
#include <filesystem>
#include <limits>

#include <fmt/format.h>

#include "document.hpp"
#include "ibl/io/file_io.hpp"
#include "io/little_endian.hpp"

namespace ibl::gltf {

namespace {

namespace fs = std::filesystem;

void appendLe32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

// tinygltf's file access: regular files only (never a device or a pipe), read through
// readFileBytes (its size limit), paths taken as they are (tinygltf's default expands them with
// wordexp).
bool regularFileExists(const std::string& path, void*) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

std::string pathAsIs(const std::string& path, void*) {
  return path;
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void*) {
  try {
    *out = readFileBytes(path);
    return true;
  } catch (const Error& e) {
    if (err) *err += e.what();
    return false;
  }
}

bool writeNothing(std::string*, const std::string&, const std::vector<unsigned char>&, void*) {
  return false;
}

// The chunks of a GLB container, each checked against the container's length.
struct GlbChunks {
  std::string_view json;
  std::span<const std::uint8_t> bin;
  bool hasBin = false;
};

GlbChunks splitGlb(std::span<const std::uint8_t> bytes, const std::string& path) {
  if (bytes.size() < 12) fail(path, "truncated GLB: no complete header");
  const std::uint32_t version = le::get32(bytes, 4), length = le::get32(bytes, 8);
  if (version != 2) fail(path, fmt::format("GLB version {} (ibl reads version 2)", version));
  if (length > bytes.size())
    fail(path, fmt::format("truncated GLB: its header says {} bytes, the file has {}", length,
                           bytes.size()));
  if (length < 20 || le::get32(bytes, 16) != 0x4E4F534Au) fail(path, "GLB without a JSON chunk");
  const std::uint32_t jsonLength = le::get32(bytes, 12);
  if (jsonLength > length - 20)
    fail(path, fmt::format("GLB JSON chunk of {} bytes runs past the end of the GLB ({} bytes)",
                           jsonLength, length));
  GlbChunks c;
  c.json = std::string_view(reinterpret_cast<const char*>(bytes.data()) + 20, jsonLength);
  const std::size_t at = 20 + static_cast<std::size_t>(jsonLength);
  if (length - at >= 8 && le::get32(bytes, at + 4) == 0x004E4942u) {  // "BIN"
    const std::uint32_t binLength = le::get32(bytes, at);
    if (binLength > length - at - 8)
      fail(path, fmt::format("GLB BIN chunk of {} bytes runs past the end of the GLB ({} bytes)",
                             binLength, length));
    c.bin = bytes.subspan(at + 8, binLength);
    c.hasBin = true;
  }
  return c;
}

// A GLB as tinygltf accepts it: `json` and the BIN chunk padded to 4 bytes.
std::vector<std::uint8_t> canonicalGlb(std::string json, const GlbChunks& chunks) {
  while (json.size() % 4) json += ' ';
  std::vector<std::uint8_t> glb;
  const std::size_t binPadded = chunks.hasBin && !chunks.bin.empty()
                                    ? std::max<std::size_t>(4, (chunks.bin.size() + 3) / 4 * 4)
                                    : 0;
  glb.reserve(28 + json.size() + binPadded);
  appendLe32(glb, 0x46546C67u);  // "glTF"
  appendLe32(glb, 2);
  appendLe32(glb, 0);  // total length, below
  appendLe32(glb, static_cast<std::uint32_t>(json.size()));
  appendLe32(glb, 0x4E4F534Au);  // "JSON"
  glb.insert(glb.end(), json.begin(), json.end());
  if (binPadded) {
    appendLe32(glb, static_cast<std::uint32_t>(binPadded));
    appendLe32(glb, 0x004E4942u);  // "BIN"
    glb.insert(glb.end(), chunks.bin.begin(), chunks.bin.end());
    glb.resize(glb.size() + binPadded - chunks.bin.size(), 0);
  }
  const auto total = static_cast<std::uint32_t>(glb.size());
  for (int i = 0; i < 4; ++i) glb[8 + i] = static_cast<std::uint8_t>(total >> (8 * i));
  return glb;
}

bool isGlb(std::span<const std::uint8_t> bytes) {
  return bytes.size() >= 4 && le::get32(bytes, 0) == 0x46546C67u;
}

// Extensions without effect on a still image of the default look, or whose effect is reported
// where it applies (texture sources without a PNG or JPEG fallback).
bool harmless(std::string_view ext) {
  return ext == "KHR_xmp_json_ld" || ext == "KHR_xmp" || ext == "KHR_animation_pointer" ||
         ext == "KHR_texture_basisu" || ext == "EXT_texture_webp" || ext == "MSFT_texture_dds" ||
         ext == "EXT_texture_avif";
}

}  // namespace

// What ibl renders of an extension (the others in extensionsUsed are a warning each).
bool implemented(std::string_view ext) {
  return ext == "KHR_draco_mesh_compression" || ext == "KHR_materials_emissive_strength" ||
         ext == "KHR_materials_sheen" || ext == "KHR_materials_variants" ||
         ext == "KHR_materials_ior" || ext == "KHR_materials_specular" ||
         ext == "KHR_materials_unlit" || ext == "KHR_materials_clearcoat" ||
         ext == "KHR_materials_iridescence" || ext == "KHR_materials_anisotropy" ||
         ext == "KHR_materials_transmission" || ext == "KHR_materials_volume" ||
         ext == "EXT_texture_webp" || ext == "KHR_texture_transform" ||
         ext == "KHR_mesh_quantization" || ext == "EXT_meshopt_compression" ||
         ext == "KHR_lights_punctual";
}

tinygltf::Model readModel(std::span<const std::uint8_t> bytes, const std::string& path,
                          PreparedJson& prepared, bool& binary) {
  const fs::path baseDir = fs::path(path).parent_path();
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({regularFileExists, pathAsIs, readWholeFile, writeNothing, nullptr});
  std::string err, warn;
  bool ok = false;
  binary = isGlb(bytes);
  if (binary) {
    const GlbChunks chunks = splitGlb(bytes, path);
    prepared = prepareJson(chunks.json, path, baseDir, chunks.bin.size());
    const std::vector<std::uint8_t> glb = canonicalGlb(std::move(prepared.text), chunks);
    if (glb.size() > std::numeric_limits<std::uint32_t>::max())
      fail(path, "GLB of 4 GiB or more (the format's limit)");
    ok = loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(),
                                     static_cast<unsigned>(glb.size()), baseDir.string());
  } else {
    prepared =
        prepareJson(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                    path, baseDir, std::nullopt);
    if (prepared.text.size() > std::numeric_limits<unsigned>::max())
      fail(path, "JSON of 4 GiB or more");
    ok = loader.LoadASCIIFromString(&model, &err, &warn, prepared.text.c_str(),
                                    static_cast<unsigned>(prepared.text.size()), baseDir.string());
    prepared.text = std::string();
  }
  if (!ok)
    fail(path,
         fmt::format("not a readable glTF 2.0 file: {}", firstLine(err.empty() ? warn : err)));
  for (const std::string& ext : model.extensionsRequired)
    if (!implemented(ext))
      fail(path, fmt::format("requires the extension {}, which ibl does not implement", ext));
  return model;
}

void GltfDocument::warnAboutExtensions() {
  for (const std::string& ext : model_.extensionsUsed)
    if (!implemented(ext) && !harmless(ext))
      warn(fmt::format("uses the extension {}, which ibl does not implement", ext),
           "rendering without it");
}

}  // namespace ibl::gltf
