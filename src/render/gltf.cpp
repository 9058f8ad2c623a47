// glTF 2.0 loading, in the order it happens:
//  1. the container (GLB chunks) and the JSON are checked and prepared for tinygltf
//     (prepareJson): Draco accessors and meshopt fallback buffers hidden, images taken out (ibl
//     reads them itself), external buffers' sizes checked against their byteLength;
//  2. tinygltf parses (readModel); EXT_meshopt_compression views are decoded;
//  3. every reference, count, offset and stride is checked against what it refers to
//     (GltfDocument::validate) with overflow-safe arithmetic, before anything is allocated for
//     it; the node tree is walked (instances);
//  4. the images the materials read are checked (their headers against their sizes) and
//     decoded; a missing or unreadable one is a warning;
//  5. the scene's memory is estimated from the checked counts and refused over the limit; the
//     primitives are read (once each, however many nodes place them), then placed in the world.
// A hostile file thus costs about its own size plus the data of what is valid in it.
#include "ibl/render/gltf.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/core/varint_decoding.h>
#include <draco/metadata/metadata_decoder.h>
#include <fmt/format.h>
#include <meshoptimizer.h>
#include <stb_image.h>
#include <tiny_gltf.h>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/json_file.hpp"

namespace ibl {

namespace {

namespace fs = std::filesystem;
using u64 = std::uint64_t;
constexpr u64 kU64Max = std::numeric_limits<u64>::max();

// ---------------------------------------------------------------------------------------------
// Small helpers

// "material 99 out of range (the file has 3)"
std::string outOfRange(std::string_view what, long long index, std::size_t count) {
  if (count == 0) return fmt::format("{} {} out of range (the file has none)", what, index);
  return fmt::format("{} {} out of range (the file has {})", what, index, count);
}

bool inRange(long long index, std::size_t count) {
  return index >= 0 && static_cast<u64>(index) < count;
}

u64 saturatingMul(u64 a, u64 b) {
  return b != 0 && a > kU64Max / b ? kU64Max : a * b;
}
u64 saturatingAdd(u64 a, u64 b) {
  return a > kU64Max - b ? kU64Max : a + b;
}

std::string firstLine(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  if (line.size() > 200) line = line.substr(0, 200) + "...";
  return line;
}

std::string formatBytes(u64 bytes) {
  if (bytes >= (u64{1} << 30))
    return fmt::format("{:.1f} GiB", static_cast<double>(bytes) / 0x1p30);
  if (bytes >= (u64{1} << 20))
    return fmt::format("{:.1f} MiB", static_cast<double>(bytes) / 0x1p20);
  if (bytes >= (u64{1} << 10))
    return fmt::format("{:.1f} KiB", static_cast<double>(bytes) / 0x1p10);
  return fmt::format("{} bytes", bytes);
}

std::uint32_t readLe32(std::span<const std::uint8_t> b, std::size_t at) {
  return b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) |
         (static_cast<std::uint32_t>(b[at + 3]) << 24);
}
std::uint32_t readBe32(const std::uint8_t* p) {
  return (static_cast<std::uint32_t>(p[0]) << 24) | (p[1] << 16) | (p[2] << 8) | p[3];
}
void appendLe32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

// The deepest nesting of arrays and objects in JSON text (strings skipped): tinygltf converts
// extensions and extras recursively, so depth is bounded before it parses.
constexpr std::size_t kMaxJsonDepth = 128;
std::size_t jsonDepth(std::string_view text) {
  std::size_t depth = 0, deepest = 0;
  bool inString = false, escape = false;
  for (const char c : text) {
    if (inString) {
      if (escape)
        escape = false;
      else if (c == '\\')
        escape = true;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

// A data URI: "data:[<mime type>][;base64],<payload>".
struct DataUri {
  std::string mimeType;
  bool base64 = false;
  std::string_view payload;
};
std::optional<DataUri> parseDataUri(std::string_view uri) {
  if (uri.substr(0, 5) != "data:") return std::nullopt;
  const std::size_t comma = uri.find(',');
  if (comma == std::string_view::npos) return DataUri{};
  std::string_view header = uri.substr(5, comma - 5);
  DataUri d;
  if (header.size() >= 7 && header.substr(header.size() - 7) == ";base64") {
    d.base64 = true;
    header.remove_suffix(7);
  }
  d.mimeType = std::string(header.substr(0, header.find(';')));
  d.payload = uri.substr(comma + 1);
  return d;
}

int base64Value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+' || c == '-') return 62;
  if (c == '/' || c == '_') return 63;
  return -1;
}

// The number of bytes base64 text decodes to (padding optional), without decoding it.
u64 base64Size(std::string_view text) {
  while (!text.empty() && text.back() == '=') text.remove_suffix(1);
  return text.size() / 4 * 3 + (text.size() % 4 == 0 ? 0 : text.size() % 4 - 1);
}

// Base64 (RFC 4648, standard or URL alphabet, padding optional); nullopt if it is not base64.
std::optional<std::vector<std::uint8_t>> decodeBase64(std::string_view text) {
  while (!text.empty() && text.back() == '=') text.remove_suffix(1);
  if (text.size() % 4 == 1) return std::nullopt;
  std::vector<std::uint8_t> out;
  out.reserve(base64Size(text));
  std::uint32_t acc = 0;
  int bits = 0;
  for (const char c : text) {
    const int v = base64Value(c);
    if (v < 0) return std::nullopt;
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>(acc >> bits));
    }
  }
  return out;
}

// A relative URI's %XX escapes decoded (RFC 3986).
std::string percentDecode(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto hex = [](char c) {
      return c >= '0' && c <= '9'   ? c - '0'
             : c >= 'a' && c <= 'f' ? c - 'a' + 10
             : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                    : -1;
    };
    if (s[i] == '%' && i + 2 < s.size() && hex(s[i + 1]) >= 0 && hex(s[i + 2]) >= 0) {
      out += static_cast<char>(hex(s[i + 1]) * 16 + hex(s[i + 2]));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
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

// ---------------------------------------------------------------------------------------------
// 1. The container and the JSON

// An image as the file gives it: ibl reads images itself, not through tinygltf.
struct ImageSource {
  std::string uri;  // an external file (as written, percent-encoded) or a data URI; or empty
  int bufferView = -1;
  std::string mimeType, name;
};

// A buffer view compressed with EXT_meshopt_compression: after prepareJson, tinygltf sees it as
// the compressed bytes; decodeMeshoptViews turns it back into `count` elements of `stride` bytes.
struct MeshoptView {
  int index = 0;
  std::size_t count = 0, stride = 0, byteLength = 0;  // byteLength: of the decoded view
  std::string mode, filter;
};

// The JSON as tinygltf is to read it, and what was taken out of it.
struct PreparedJson {
  std::string text;
  std::vector<ImageSource> images;
  std::vector<MeshoptView> meshopt;
};

const nlohmann::json* member(const nlohmann::json& o, const char* key) {
  if (!o.is_object()) return nullptr;
  const auto it = o.find(key);
  return it == o.end() ? nullptr : &*it;
}

std::optional<long long> integerMember(const nlohmann::json& o, const char* key) {
  const nlohmann::json* v = member(o, key);
  if (!v || !v->is_number_integer()) return std::nullopt;
  return v->is_number_unsigned() && v->get<u64>() > static_cast<u64>(kU64Max >> 1)
             ? std::numeric_limits<long long>::max()
             : v->get<long long>();
}

// Buffers: a data URI must hold byteLength bytes, an external file must exist and be that long,
// a GLB's buffer without a uri must fit in its BIN chunk (`binSize`, nullopt for a .gltf).
// tinygltf checks the same, with messages that name neither the buffer nor the file well.
void checkBuffers(const nlohmann::json& gltf, const std::string& path, const fs::path& baseDir,
                  std::optional<std::size_t> binSize) {
  const nlohmann::json* buffers = member(gltf, "buffers");
  if (!buffers || !buffers->is_array()) return;
  for (std::size_t k = 0; k < buffers->size(); ++k) {
    const nlohmann::json& b = (*buffers)[k];
    const std::optional<long long> length = integerMember(b, "byteLength");
    const nlohmann::json* uri = member(b, "uri");
    if (length && !uri && binSize && static_cast<u64>(*length) > *binSize)
      fail(path,
           fmt::format("buffer {}: its byteLength says {}, the GLB's BIN chunk holds {} bytes", k,
                       *length, *binSize));
    if (!length || !uri || !uri->is_string()) continue;
    const auto& text = uri->get_ref<const std::string&>();
    if (const auto data = parseDataUri(text)) {
      if (!data->base64) fail(path, fmt::format("buffer {}: its data URI is not base64", k));
      const u64 size = base64Size(data->payload);
      if (size != static_cast<u64>(*length))
        fail(path, fmt::format("buffer {}: its data URI holds {} bytes, its byteLength says {}", k,
                               size, *length));
      continue;
    }
    const fs::path file = baseDir / percentDecode(text);
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
      fail(path, fmt::format("buffer {}: '{}' is missing", k, text));
    const u64 size = fs::file_size(file, ec);
    if (!ec && size != static_cast<u64>(*length))
      fail(path, fmt::format("buffer {}: '{}' has {} bytes, its byteLength says {}", k, text, size,
                             *length));
  }
}

// tinygltf rejects an index accessor without a buffer view with a message that does not say
// which primitive: say it first (after hideDracoAccessors: Draco primitives' accessors have none).
void checkIndexAccessors(const nlohmann::json& gltf, const std::string& path) {
  const nlohmann::json* meshes = member(gltf, "meshes");
  const nlohmann::json* accessors = member(gltf, "accessors");
  const std::size_t accessorCount = accessors && accessors->is_array() ? accessors->size() : 0;
  if (!meshes || !meshes->is_array()) return;
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const nlohmann::json* prims = member((*meshes)[m], "primitives");
    if (!prims || !prims->is_array()) continue;
    for (std::size_t p = 0; p < prims->size(); ++p) {
      const std::optional<long long> indices = integerMember((*prims)[p], "indices");
      if (!indices) continue;
      const std::string where = fmt::format("mesh {} primitive {}", m, p);
      if (!inRange(*indices, accessorCount))
        fail(path, fmt::format("{}: indices: {}", where,
                               outOfRange("accessor", *indices, accessorCount)));
      if (!integerMember((*accessors)[static_cast<std::size_t>(*indices)], "bufferView"))
        fail(path, fmt::format("{}: index accessor {} has no buffer view", where, *indices));
    }
  }
}

// Debian's tinygltf is built without Draco and rejects the accessors of Draco primitives (they
// have no buffer view). Those accessors are not needed (the Draco stream has the data), so
// drop them from such primitives before tinygltf sees the JSON.
void hideDracoAccessors(nlohmann::json& gltf) {
  nlohmann::json* meshes = gltf.contains("meshes") ? &gltf["meshes"] : nullptr;
  if (!meshes || !meshes->is_array()) return;
  for (auto& mesh : *meshes) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
      continue;
    for (auto& prim : mesh["primitives"]) {
      const nlohmann::json* ext = member(prim, "extensions");
      if (!ext || !member(*ext, "KHR_draco_mesh_compression")) continue;
      prim.erase("indices");
      prim["attributes"] = nlohmann::json::object();
    }
  }
}

// EXT_meshopt_compression stores each compressed view's bytes elsewhere and may give the view's
// own buffer no data at all (a "fallback" buffer: no uri, or a GLB buffer that is not the BIN
// chunk), which tinygltf rejects. Point each compressed view at its compressed bytes, give
// fallback buffers a 4-byte placeholder, and list the views to decode once tinygltf is done.
void hideMeshoptFallbacks(nlohmann::json& gltf, const std::string& path,
                          std::vector<MeshoptView>& views) {
  if (!gltf.contains("bufferViews") || !gltf["bufferViews"].is_array()) return;
  const auto extensionOf = [](const nlohmann::json& o) -> const nlohmann::json* {
    const nlohmann::json* e = member(o, "extensions");
    return e ? member(*e, "EXT_meshopt_compression") : nullptr;
  };
  std::vector<bool> fallback;
  if (gltf.contains("buffers") && gltf["buffers"].is_array())
    for (const auto& b : gltf["buffers"]) {
      const nlohmann::json* e = extensionOf(b);
      fallback.push_back(e && e->is_object() && e->value("fallback", false));
    }
  auto& bufferViews = gltf["bufferViews"];
  for (std::size_t i = 0; i < bufferViews.size(); ++i) {
    auto& bv = bufferViews[i];
    const nlohmann::json* e = extensionOf(bv);
    if (!e) {
      const std::optional<long long> buffer = integerMember(bv, "buffer");
      if (buffer && inRange(*buffer, fallback.size()) &&
          fallback[static_cast<std::size_t>(*buffer)])
        fail(path,
             fmt::format("buffer view {} reads fallback buffer {}, which has no data", i, *buffer));
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
  for (std::size_t b = 0; b < fallback.size(); ++b)
    if (fallback[b])
      gltf["buffers"][b] = {{"byteLength", 4},
                            {"uri", "data:application/octet-stream;base64,AAAAAA=="}};
}

// Takes the images out of the JSON (tinygltf would read and decode them all, reading image
// buffer views without checking their range); readImages reads those the materials use.
std::vector<ImageSource> takeImages(nlohmann::json& gltf, const std::string& path) {
  std::vector<ImageSource> images;
  if (!gltf.contains("images")) return images;
  nlohmann::json& list = gltf["images"];
  if (!list.is_array()) fail(path, "\"images\" is not an array");
  for (std::size_t k = 0; k < list.size(); ++k) {
    nlohmann::json& o = list[k];
    if (!o.is_object()) fail(path, fmt::format("image {} is not a JSON object", k));
    ImageSource s;
    const nlohmann::json* uri = member(o, "uri");
    const nlohmann::json* view = member(o, "bufferView");
    if (uri && view) fail(path, fmt::format("image {} has both a uri and a bufferView", k));
    if (!uri && !view) fail(path, fmt::format("image {} has neither a uri nor a bufferView", k));
    if (uri) {
      if (!uri->is_string()) fail(path, fmt::format("image {}: its uri is not a string", k));
      s.uri = std::move(o["uri"].get_ref<std::string&>());
    } else {
      const std::optional<long long> v = integerMember(o, "bufferView");
      if (!v || *v < 0 || *v > std::numeric_limits<int>::max())
        fail(path, fmt::format("image {}: its bufferView is not an index", k));
      s.bufferView = static_cast<int>(*v);
    }
    if (const nlohmann::json* m = member(o, "mimeType"); m && m->is_string())
      s.mimeType = m->get<std::string>();
    if (const nlohmann::json* n = member(o, "name"); n && n->is_string())
      s.name = n->get<std::string>();
    images.push_back(std::move(s));
  }
  gltf.erase("images");
  return images;
}

// Whether ibl reads the extension `name` on an object of `kind` (the key of the array or object
// holding it; "" for the file's root). EXT_meshopt_compression is read by hideMeshoptFallbacks.
bool readsExtension(const std::string& kind, const std::string& name) {
  return (kind.empty() && name == "KHR_lights_punctual") ||
         (kind == "nodes" && name == "KHR_lights_punctual") ||
         (kind == "materials" &&
          (name == "KHR_materials_sheen" || name == "KHR_materials_emissive_strength")) ||
         (kind == "primitives" && name == "KHR_draco_mesh_compression") ||
         ((kind == "bufferViews" || kind == "buffers") && name == "EXT_meshopt_compression");
}

// The number of values in a JSON tree, up to `limit`.
std::size_t valueCount(const nlohmann::json& v, std::size_t limit) {
  std::size_t n = 1;
  if (v.is_structured())
    for (const auto& child : v) {
      n += valueCount(child, limit - std::min(n, limit));
      if (n >= limit) return n;
    }
  return n;
}

// tinygltf converts every "extras" and every extension to its generic values, some 160 bytes per
// JSON value (a file of 10 MB of extras took 1 GB): keep only the extensions ibl reads, where it
// reads them, each within a size a real one never reaches; of the others, their names (for the
// warnings and `ibl info`). `kind` is the key of the array or object holding `v`, `where` names
// it for messages ("mesh 0 primitive 1").
void stripUnread(nlohmann::json& v, const std::string& kind, const std::string& where,
                 const std::string& path) {
  if (v.is_array()) {
    const std::string item = kind == "meshes"       ? "mesh"
                             : kind == "materials"  ? "material"
                             : kind == "nodes"      ? "node"
                             : kind == "primitives" ? "primitive"
                                                    : kind;
    for (std::size_t i = 0; i < v.size(); ++i)
      stripUnread(v[i], kind, fmt::format("{}{} {}", where.empty() ? "" : where + " ", item, i),
                  path);
    return;
  }
  if (!v.is_object()) return;
  v.erase("extras");
  for (auto it = v.begin(); it != v.end(); ++it) {
    if (it.key() != "extensions") {
      stripUnread(it.value(), it.key(), where, path);
      continue;
    }
    if (!it.value().is_object()) continue;  // tinygltf's to refuse
    for (auto ext = it.value().begin(); ext != it.value().end(); ++ext) {
      const std::string& name = ext.key();
      if (!readsExtension(kind, name)) {
        ext.value() = nlohmann::json::object();
        continue;
      }
      // The lights of a file: 16 values at most each (type, color, intensity, range, spot, name).
      const nlohmann::json* lights = kind.empty() ? member(ext.value(), "lights") : nullptr;
      const std::size_t limit =
          lights && lights->is_array() ? 64 * (lights->size() + 1) : std::size_t{256};
      if (valueCount(ext.value(), limit + 1) > limit)
        fail(path, fmt::format("{}{} holds more values than the extension has",
                               where.empty() ? "" : where + ": ", name));
    }
  }
}

// Builds the DOM of a JSON text as nlohmann's parser does, but leaves out each member whose key
// path `keep` rejects, with everything under it, as it reads: their values are never stored.
// Linear in the text (nlohmann's own callback parser rescans an array's elements each time an
// object in it ends: 100 000 nodes took 6.6 s). keys[d] is the key of the member at depth d
// (the number of containers open around it) on the way to the current one.
class FilteringDomBuilder {
 public:
  using Json = nlohmann::json;
  using KeepFn = bool (*)(const std::vector<std::string>& keys, std::size_t depth);
  // `text`: what is parsed, for the place of an error.
  FilteringDomBuilder(Json& root, KeepFn keep, std::string_view text)
      : root_(root), keep_(keep), text_(text) {}

  bool null() { return put(nullptr); }
  bool boolean(bool v) { return put(v); }
  bool number_integer(Json::number_integer_t v) { return put(v); }
  bool number_unsigned(Json::number_unsigned_t v) { return put(v); }
  bool number_float(Json::number_float_t v, const std::string&) { return put(v); }
  bool string(Json::string_t& v) { return put(std::move(v)); }
  bool binary(Json::binary_t& v) { return put(Json::binary(std::move(v))); }
  bool start_object(std::size_t) { return open(Json::object()); }
  bool start_array(std::size_t) { return open(Json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(Json::string_t& k) {
    if (skipped_ > 0) return true;
    const std::size_t depth = open_.size();
    if (keys_.size() <= depth) keys_.resize(depth + 1);
    keys_[depth] = k;
    skipNext_ = !keep_(keys_, depth);
    if (!skipNext_) key_ = std::move(k);
    return true;
  }
  bool parse_error(std::size_t charactersRead, const std::string& token,
                   const nlohmann::detail::exception& e) {
    error_ = describeJsonError(text_, charactersRead, token, e.id, e.what());
    return false;
  }
  const std::string& error() const { return error_; }

 private:
  // Places `v` where the parser is: the root, the next element of an array, or the member named
  // by the last key. Returns where it went.
  Json* insert(Json&& v) {
    if (open_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Json& parent = *open_.back();
    if (parent.is_array()) {
      parent.push_back(std::move(v));
      return &parent.back();
    }
    Json& member = parent[key_];
    member = std::move(v);
    return &member;
  }
  bool put(Json&& v) {
    if (skipped_ == 0 && !std::exchange(skipNext_, false)) insert(std::move(v));
    return true;
  }
  bool open(Json&& container) {
    if (skipped_ > 0 || std::exchange(skipNext_, false)) {
      ++skipped_;
      return true;
    }
    open_.push_back(insert(std::move(container)));
    return true;
  }
  bool close() {
    if (skipped_ > 0)
      --skipped_;
    else
      open_.pop_back();
    return true;
  }

  Json& root_;
  KeepFn keep_;
  std::string_view text_;
  std::vector<Json*> open_;  // the containers being filled, outermost first
  std::vector<std::string> keys_;
  std::string key_;
  std::string error_;
  bool skipNext_ = false;  // the next value is a rejected member's
  int skipped_ = 0;        // containers open inside a rejected member
};

// Whether the member at keys[depth] is kept: not "extras" (anything an exporter adds), nor
// the contents of an extension ibl does not read where it is.
bool keepMember(const std::vector<std::string>& keys, std::size_t d) {
  if (keys[d] == "extras") return false;
  if (d < 3 || keys[d - 2] != "extensions") return true;  // not inside an extension
  // keys[d - 1] is the extension; "extensions" is a member of the root (d == 3) or of an
  // element of the array at keys[d - 4] (a material, node or primitive).
  return readsExtension(d == 3 ? "" : d >= 5 ? keys[d - 4] : "-", keys[d - 1]);
}

PreparedJson prepareJson(std::string_view text, const std::string& path, const fs::path& baseDir,
                         std::optional<std::size_t> binSize) {
  if (jsonDepth(text) > kMaxJsonDepth)
    fail(path, fmt::format("not a readable glTF 2.0 file: JSON nested deeper than {} levels",
                           kMaxJsonDepth));
  nlohmann::json j;
  FilteringDomBuilder builder(j, keepMember, text);
  try {
    if (!nlohmann::json::sax_parse(text.begin(), text.end(), &builder))
      fail(path, fmt::format("not a readable glTF 2.0 file: invalid JSON: {}", builder.error()));
  } catch (const nlohmann::json::exception& e) {
    fail(path, fmt::format("not a readable glTF 2.0 file: invalid JSON ({})", firstLine(e.what())));
  }
  if (!j.is_object()) fail(path, "not a readable glTF 2.0 file: the JSON is not an object");
  PreparedJson out;
  try {
    hideDracoAccessors(j);
    hideMeshoptFallbacks(j, path, out.meshopt);
    checkBuffers(j, path, baseDir, binSize);
    checkIndexAccessors(j, path);
    out.images = takeImages(j, path);
    stripUnread(j, "", "", path);
    out.text = j.dump();
  } catch (const nlohmann::json::exception& e) {
    fail(path, fmt::format("not a readable glTF 2.0 file: {}", firstLine(e.what())));
  }
  return out;
}

// The chunks of a GLB container, each checked against the container's length.
struct GlbChunks {
  std::string_view json;
  std::span<const std::uint8_t> bin;
  bool hasBin = false;
};
GlbChunks splitGlb(std::span<const std::uint8_t> bytes, const std::string& path) {
  if (bytes.size() < 12) fail(path, "truncated GLB: no complete header");
  const std::uint32_t version = readLe32(bytes, 4), length = readLe32(bytes, 8);
  if (version != 2) fail(path, fmt::format("GLB version {} (ibl reads version 2)", version));
  if (length > bytes.size())
    fail(path, fmt::format("truncated GLB: its header says {} bytes, the file has {}", length,
                           bytes.size()));
  if (length < 20 || readLe32(bytes, 16) != 0x4E4F534Au) fail(path, "GLB without a JSON chunk");
  const std::uint32_t jsonLength = readLe32(bytes, 12);
  if (jsonLength > length - 20)
    fail(path, fmt::format("GLB JSON chunk of {} bytes runs past the end of the GLB ({} bytes)",
                           jsonLength, length));
  GlbChunks c;
  c.json = std::string_view(reinterpret_cast<const char*>(bytes.data()) + 20, jsonLength);
  const std::size_t at = 20 + static_cast<std::size_t>(jsonLength);
  if (length - at >= 8 && readLe32(bytes, at + 4) == 0x004E4942u) {  // "BIN"
    const std::uint32_t binLength = readLe32(bytes, at);
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

// ---------------------------------------------------------------------------------------------
// 2. tinygltf, and the meshopt views

bool isGlb(std::span<const std::uint8_t> bytes) {
  return bytes.size() >= 4 && readLe32(bytes, 0) == 0x46546C67u;
}

// What ibl renders of an extension (the others in extensionsUsed are a warning each).
bool implemented(std::string_view ext) {
  return ext == "KHR_draco_mesh_compression" || ext == "KHR_materials_emissive_strength" ||
         ext == "KHR_materials_sheen" || ext == "KHR_mesh_quantization" ||
         ext == "EXT_meshopt_compression" || ext == "KHR_lights_punctual";
}
// Extensions without effect on a still image of the default look, or whose effect is reported
// where it applies (texture sources without a PNG or JPEG fallback).
bool harmless(std::string_view ext) {
  return ext == "KHR_materials_variants" || ext == "KHR_xmp_json_ld" || ext == "KHR_xmp" ||
         ext == "KHR_animation_pointer" || ext == "KHR_texture_basisu" ||
         ext == "EXT_texture_webp" || ext == "MSFT_texture_dds" || ext == "EXT_texture_avif";
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

// Byte ranges of buffers, each to be decoded once: a range may be added again as it is (the
// caller reuses what it made of it), not overlap another in part.
class DisjointRanges {
 public:
  // Whether [start, end) of `buffer` equals or misses every range added so far; adds it.
  bool add(int buffer, u64 start, u64 end) {
    if (start == end) return true;
    std::map<u64, u64>& ranges = ranges_[buffer];
    const auto next = ranges.lower_bound(start);
    if (next != ranges.end() && next->first == start && next->second == end) return true;
    if (next != ranges.end() && next->first < end) return false;
    if (next != ranges.begin() && std::prev(next)->second > start) return false;
    ranges.emplace(start, end);
    return true;
  }

 private:
  std::map<int, std::map<u64, u64>> ranges_;
};

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

// ---------------------------------------------------------------------------------------------
// 3. Accessors

std::size_t componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

const char* typeName(int components) {
  switch (components) {
    case 1:
      return "SCALAR";
    case 2:
      return "VEC2";
    case 3:
      return "VEC3";
    case 4:
      return "VEC4";
    default:
      return "a matrix";
  }
}

// An accessor, checked: where its elements are and how to read them.
struct AccessorLayout {
  const std::uint8_t* data = nullptr;  // the first element; null: every element is zero
  std::size_t stride = 0, count = 0, elementSize = 0;
  int componentType = 0, components = 0;
  bool normalized = false, matrix = false;
  // Sparse (glTF 2.0 3.6.2.3): `sparseCount` increasing element indices, and their values
  // (tightly packed elements).
  std::size_t sparseCount = 0;
  const std::uint8_t* sparseIndices = nullptr;
  int sparseIndexType = 0;
  const std::uint8_t* sparseValues = nullptr;
};

std::uint32_t unsignedAt(const std::uint8_t* p, int componentType, std::size_t i) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return p[i];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p + 2 * i, 2);
      return v;
    }
    default: {
      std::uint32_t v;
      std::memcpy(&v, p + 4 * i, 4);
      return v;
    }
  }
}

float componentAt(const std::uint8_t* p, int type, int c, bool normalized) {
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
    default: {  // UNSIGNED_INT: not an attribute type (checked before reading)
      std::uint32_t v;
      std::memcpy(&v, p + 4 * c, 4);
      return static_cast<float>(v);
    }
  }
}

// The address of element i, its sparse value where there is one (binary search among the
// increasing indices); null for an element that is zero.
const std::uint8_t* elementAt(const AccessorLayout& a, std::size_t i) {
  if (a.sparseCount) {
    std::size_t lo = 0, hi = a.sparseCount;
    while (lo < hi) {
      const std::size_t mid = lo + (hi - lo) / 2;
      const std::uint32_t at = unsignedAt(a.sparseIndices, a.sparseIndexType, mid);
      if (at == i) return a.sparseValues + mid * a.elementSize;
      if (at < i)
        lo = mid + 1;
      else
        hi = mid;
    }
  }
  return a.data ? a.data + i * a.stride : nullptr;
}

void readFloats(const AccessorLayout& a, std::size_t i, float* out) {
  const std::uint8_t* p = elementAt(a, i);
  for (int c = 0; c < a.components; ++c)
    out[c] = p ? componentAt(p, a.componentType, c, a.normalized) : 0.0f;
}

std::uint32_t readIndex(const AccessorLayout& a, std::size_t i) {
  const std::uint8_t* p = elementAt(a, i);
  return p ? unsignedAt(p, a.componentType, 0) : 0;
}

// ---------------------------------------------------------------------------------------------
// 4. Images

// The smallest number of bytes a PNG or JPEG of its declared size can hold, so that a header
// claiming a large image over a few bytes of data is refused before the decoder allocates for it.
// PNG: deflate expands at most 1032 times, and the filtered rows take height x (1 + row bytes).
// JPEG: every 8x8 block takes at least a bit in some scan, and no real JPEG holds fewer than one
// byte per 4096 pixels (the densest, a flat gray progressive image, takes one per 512).
struct ImageProbe {
  int width = 0, height = 0;
  std::string problem;  // empty: readable
};

ImageProbe probeImage(std::span<const std::uint8_t> b) {
  ImageProbe r;
  static constexpr std::uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (b.size() >= 8 && std::memcmp(b.data(), kPng, 8) == 0) {
    if (b.size() < 33 || std::memcmp(b.data() + 12, "IHDR", 4) != 0) {
      r.problem = "a PNG without its IHDR chunk";
      return r;
    }
    const u64 width = readBe32(b.data() + 16), height = readBe32(b.data() + 20);
    const unsigned depth = b[24], colorType = b[25];
    const unsigned channels = colorType == 0   ? 1
                              : colorType == 2 ? 3
                              : colorType == 3 ? 1
                              : colorType == 4 ? 2
                              : colorType == 6 ? 4
                                               : 0;
    if (!channels || !(depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16)) {
      r.problem = "a PNG of an invalid color type or bit depth";
      return r;
    }
    if (width == 0 || height == 0 || width > kMaxImageDimension || height > kMaxImageDimension ||
        width * height > kMaxImagePixels) {
      r.problem = fmt::format("a PNG of {}x{} pixels (ibl reads up to {}x{}, {} pixels)", width,
                              height, kMaxImageDimension, kMaxImageDimension, kMaxImagePixels);
      return r;
    }
    u64 idat = 0;
    for (std::size_t at = 8; at + 8 <= b.size();) {
      const u64 length = readBe32(b.data() + at);
      if (std::memcmp(b.data() + at + 4, "IDAT", 4) == 0) idat += length;
      if (std::memcmp(b.data() + at + 4, "IEND", 4) == 0 || length > b.size() - at - 8) break;
      at += 12 + static_cast<std::size_t>(length);
    }
    const u64 rows = height * (1 + (width * depth * channels + 7) / 8);
    if (rows > 1032 * idat + 1024) {
      r.problem = fmt::format("a PNG whose {} bytes of image data cannot hold {}x{} pixels", idat,
                              width, height);
      return r;
    }
    r.width = static_cast<int>(width);
    r.height = static_cast<int>(height);
    return r;
  }
  if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) {
    int w = 0, h = 0, comp = 0;
    if (b.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
        !stbi_info_from_memory(b.data(), static_cast<int>(b.size()), &w, &h, &comp)) {
      r.problem = fmt::format("a JPEG whose header cannot be read ({})", stbi_failure_reason());
      return r;
    }
    const u64 pixels = static_cast<u64>(w) * static_cast<u64>(h);
    if (w > kMaxImageDimension || h > kMaxImageDimension || pixels > kMaxImagePixels) {
      r.problem = fmt::format("a JPEG of {}x{} pixels (ibl reads up to {}x{}, {} pixels)", w, h,
                              kMaxImageDimension, kMaxImageDimension, kMaxImagePixels);
      return r;
    }
    if (pixels > 4096 * u64{b.size()}) {
      r.problem = fmt::format("a JPEG whose {} bytes cannot hold {}x{} pixels", b.size(), w, h);
      return r;
    }
    r.width = w;
    r.height = h;
    return r;
  }
  r.problem = "not a PNG or JPEG image (glTF 2.0 images are one or the other)";
  return r;
}

// ---------------------------------------------------------------------------------------------
// 5. Geometry

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

// A glTF sampler's wrap mode (an OpenGL enum; absent: REPEAT).
Wrap wrapOf(int mode) {
  if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return Wrap::ClampToEdge;
  if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return Wrap::MirroredRepeat;
  return Wrap::Repeat;
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

// The material slots ibl reads, as (name, texture info): glTF's five and KHR_materials_sheen's
// two.
struct SlotRef {
  std::string name;
  int index = -1, texCoord = 0;
};
std::vector<SlotRef> materialSlots(const tinygltf::Material& m, const std::string& path,
                                   const std::string& where) {
  const auto& pbr = m.pbrMetallicRoughness;
  std::vector<SlotRef> slots = {
      {"baseColorTexture", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord},
      {"metallicRoughnessTexture", pbr.metallicRoughnessTexture.index,
       pbr.metallicRoughnessTexture.texCoord},
      {"normalTexture", m.normalTexture.index, m.normalTexture.texCoord},
      {"occlusionTexture", m.occlusionTexture.index, m.occlusionTexture.texCoord},
      {"emissiveTexture", m.emissiveTexture.index, m.emissiveTexture.texCoord}};
  const auto sheen = m.extensions.find("KHR_materials_sheen");
  if (sheen != m.extensions.end())
    for (const char* name : {"sheenColorTexture", "sheenRoughnessTexture"}) {
      if (!sheen->second.IsObject() || !sheen->second.Has(name)) continue;
      const tinygltf::Value& t = sheen->second.Get(name);
      const std::string at = where + ": KHR_materials_sheen " + name;
      slots.push_back({name, extensionIndex(t, "index", path, at).value_or(-1),
                       extensionIndex(t, "texCoord", path, at).value_or(0)});
    }
  return slots;
}

// ---------------------------------------------------------------------------------------------
// The document: the model, checked, and what is read from it

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

class GltfDocument {
 public:
  GltfDocument(std::span<const std::uint8_t> bytes, const std::string& path,
               const GltfLoadOptions& options)
      : path_(path), options_(options) {
    PreparedJson prepared;
    model_ = readModel(bytes, path, prepared, binary_);
    images_ = std::move(prepared.images);
    decodeMeshoptViews(model_, prepared.meshopt, path);
    for (const MeshoptView& v : prepared.meshopt) meshoptViews_.insert(v.index);
    validate();
    walkScene();
    warnAboutExtensions();
  }

  Scene load() {
    Scene scene;
    scene.textures = readTextures(true);
    scene.materials = readMaterials(scene.textures);
    std::vector<std::size_t> uses(model_.meshes.size(), 0);
    for (const Instance& i : instances_) ++uses[static_cast<std::size_t>(nodes()[i.node].mesh)];
    prepareGeometry(uses);
    const int defaultMaterial = static_cast<int>(scene.materials.size()) - 1;
    for (const Instance& instance : instances_) {
      const int m = nodes()[instance.node].mesh;
      const auto& prims = model_.meshes[static_cast<std::size_t>(m)].primitives;
      for (std::size_t p = 0; p < prims.size(); ++p) {
        PrimitiveData* data = primitive(m, p);
        if (!data) continue;
        Mesh mesh;
        if (--data->instancesLeft == 0)
          mesh = std::move(data->mesh);  // its last instance
        else
          mesh = data->mesh;
        mesh.material = prims[p].material >= 0 ? prims[p].material : defaultMaterial;
        mesh.names = namesOf(instance.node);
        placeInWorld(mesh, instance.world,
                     scene.materials[static_cast<std::size_t>(mesh.material)].normalTexture);
        checkFinite(mesh, m, p, instance.node);
        if (!mesh.indices.empty()) scene.meshes.push_back(std::move(mesh));
      }
    }
    if (camera_)
      scene.camera =
          cameraOf(model_.cameras[static_cast<std::size_t>(camera_->first)], camera_->second);
    for (const Instance& i : lightInstances_) scene.lights.push_back(lightOf(i));
    if (scene.meshes.empty()) fail(path_, "no triangle meshes to render");
    return scene;
  }

  // What a mesh instance of `node` answers to: the glTF mesh's name, the node's and its
  // ancestors' (unnamed ones left out).
  std::vector<std::string> namesOf(int node) const {
    std::vector<std::string> names;
    const std::string& mesh =
        model_.meshes[static_cast<std::size_t>(nodes()[static_cast<std::size_t>(node)].mesh)].name;
    if (!mesh.empty()) names.push_back(mesh);
    for (int at = node; at >= 0; at = parents_[static_cast<std::size_t>(at)])
      if (!nodes()[static_cast<std::size_t>(at)].name.empty())
        names.push_back(nodes()[static_cast<std::size_t>(at)].name);
    return names;
  }

  GltfSummary describe() {
    GltfSummary s;
    s.binary = binary_;
    s.generator = model_.asset.generator;
    s.extensionsUsed = model_.extensionsUsed;
    s.extensionsRequired = model_.extensionsRequired;
    s.scene = sceneIndex_;
    s.scenes = model_.scenes.size();
    for (std::size_t n = 0; n < nodes().size(); ++n) {
      const tinygltf::Node& node = nodes()[n];
      s.nodes.push_back(
          {node.name, node.mesh, node.camera, lightIndexOf(node), parents_[n], inScene_[n]});
    }
    // Every mesh is read (one instance each at least, for the memory estimate), its counts of
    // one instance reported; the scene's totals and bounds count its instances.
    std::vector<std::size_t> uses(model_.meshes.size(), 0);
    for (const Instance& i : instances_) ++uses[static_cast<std::size_t>(nodes()[i.node].mesh)];
    std::vector<std::size_t> atLeastOnce = uses;
    for (auto& u : atLeastOnce) u = std::max<std::size_t>(u, 1);
    prepareGeometry(atLeastOnce);
    for (std::size_t m = 0; m < model_.meshes.size(); ++m) {
      const tinygltf::Mesh& mesh = model_.meshes[m];
      GltfSummary::Mesh info;
      info.name = mesh.name;
      info.primitives = mesh.primitives.size();
      info.instances = uses[m];
      std::set<std::string> compression;
      for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
        const tinygltf::Primitive& prim = mesh.primitives[p];
        if (prim.extensions.count("KHR_draco_mesh_compression"))
          compression.insert("KHR_draco_mesh_compression");
        for (const auto& [name, accessor] : prim.attributes)
          if (meshoptViews_.count(accessors()[static_cast<std::size_t>(accessor)].bufferView))
            compression.insert("EXT_meshopt_compression");
        if (prim.indices >= 0 &&
            meshoptViews_.count(accessors()[static_cast<std::size_t>(prim.indices)].bufferView))
          compression.insert("EXT_meshopt_compression");
        const PrimitiveData* data = primitive(static_cast<int>(m), p);
        if (!data) continue;
        ++info.trianglePrimitives;
        info.triangles += data->mesh.indices.size() / 3;
        info.vertices += data->mesh.positions.size();
      }
      info.compression.assign(compression.begin(), compression.end());
      s.meshes.push_back(std::move(info));
    }
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const Instance& instance : instances_) {
      const int m = nodes()[instance.node].mesh;
      for (std::size_t p = 0; p < model_.meshes[static_cast<std::size_t>(m)].primitives.size();
           ++p) {
        const PrimitiveData* data = primitive(m, p);
        if (!data || data->mesh.indices.empty()) continue;
        ++s.meshInstances;
        s.triangles += data->mesh.indices.size() / 3;
        s.vertices += data->mesh.positions.size();
        for (const glm::vec3& v : data->mesh.positions) {
          const glm::vec3 w = glm::vec3(instance.world * glm::vec4(v, 1.0f));
          lo = glm::min(lo, w);
          hi = glm::max(hi, w);
        }
      }
    }
    if (s.triangles > 0) {
      s.hasBounds = true;
      s.boundsMin = lo;
      s.boundsMax = hi;
    }
    readTextures(false);  // the warnings about them
    for (std::size_t k = 0; k < model_.materials.size(); ++k) {
      const tinygltf::Material& m = model_.materials[k];
      GltfSummary::Material info;
      info.name = m.name;
      const auto& pbr = m.pbrMetallicRoughness;
      for (int c = 0; c < 4; ++c)
        info.baseColor[c] = static_cast<float>(pbr.baseColorFactor[static_cast<std::size_t>(c)]);
      info.metallic = static_cast<float>(pbr.metallicFactor);
      info.roughness = static_cast<float>(pbr.roughnessFactor);
      info.emissive = emissiveOf(m);
      info.alphaMode = m.alphaMode.empty() ? "OPAQUE" : m.alphaMode;
      info.doubleSided = m.doubleSided;
      for (const SlotRef& slot : materialSlots(m, path_, materialLabel(k)))
        if (slot.index >= 0 && std::find(info.textures.begin(), info.textures.end(), slot.index) ==
                                   info.textures.end())
          info.textures.push_back(slot.index);
      for (const auto& [name, value] : m.extensions) {
        info.extensions.push_back(name);
        if (!implemented(name)) info.unsupported.push_back(name);
      }
      s.materials.push_back(std::move(info));
    }
    for (std::size_t t = 0; t < model_.textures.size(); ++t) {
      GltfSummary::Texture info;
      info.image = model_.textures[t].source;
      info.used = usedTextures_.count(static_cast<int>(t)) > 0;
      if (info.image >= 0) {
        const ImageSource& src = images_[static_cast<std::size_t>(info.image)];
        info.source = sourceName(info.image);
        info.mimeType = src.mimeType;
        const ImageState& state = imageState(info.image);
        info.width = state.probe.width;
        info.height = state.probe.height;
        info.problem = state.missing ? "missing" : state.probe.problem;
      } else {
        info.problem = noSourceProblem(static_cast<int>(t));
      }
      s.textures.push_back(std::move(info));
    }
    std::vector<std::size_t> lightUses(model_.lights.size(), 0),
        cameraUses(model_.cameras.size(), 0);
    for (const Instance& i : lightInstances_)
      ++lightUses[static_cast<std::size_t>(lightIndexOf(nodes()[i.node]))];
    for (std::size_t n = 0; n < nodes().size(); ++n)
      if (inScene_[n] && nodes()[n].camera >= 0)
        ++cameraUses[static_cast<std::size_t>(nodes()[n].camera)];
    for (std::size_t k = 0; k < model_.lights.size(); ++k) {
      const tinygltf::Light& l = model_.lights[k];
      GltfSummary::Light info;
      info.name = l.name;
      info.type = l.type;
      info.intensity = l.intensity;
      if (l.color.size() == 3)
        info.color = glm::vec3(static_cast<float>(l.color[0]), static_cast<float>(l.color[1]),
                               static_cast<float>(l.color[2]));
      info.range = l.range;
      info.innerConeAngle = l.spot.innerConeAngle;
      info.outerConeAngle = l.spot.outerConeAngle;
      info.instances = lightUses[k];
      s.lights.push_back(std::move(info));
    }
    for (std::size_t k = 0; k < model_.cameras.size(); ++k) {
      const tinygltf::Camera& c = model_.cameras[k];
      GltfSummary::Camera info;
      info.name = c.name;
      info.type = c.type;
      if (c.type == "orthographic") {
        info.xmag = c.orthographic.xmag;
        info.ymag = c.orthographic.ymag;
        info.znear = c.orthographic.znear;
        info.zfar = c.orthographic.zfar;
      } else {
        info.yfov = c.perspective.yfov;
        info.aspectRatio = c.perspective.aspectRatio;
        info.znear = c.perspective.znear;
        info.zfar = c.perspective.zfar;
      }
      info.instances = cameraUses[k];
      s.cameras.push_back(std::move(info));
    }
    s.warnings = warnings_;
    return s;
  }

 private:
  const std::vector<tinygltf::Node>& nodes() const { return model_.nodes; }
  const std::vector<tinygltf::Accessor>& accessors() const { return model_.accessors; }

  // A warning, or with strict an error: `problem`, then what ibl does instead.
  void warn(const std::string& problem, const std::string& instead) {
    if (options_.strict) fail(path_, problem);
    warnings_.push_back(problem + "; " + instead);
    if (options_.warn) options_.warn(path_ + ": " + warnings_.back());
  }

  [[noreturn]] void error(const std::string& problem) const { fail(path_, problem); }

  static std::string materialLabel(std::size_t k) { return fmt::format("material {}", k); }

  // --- 3. Checks --------------------------------------------------------------------------

  void validate() {
    validateBufferViews();
    layouts_.resize(accessors().size());
    for (std::size_t k = 0; k < accessors().size(); ++k) layouts_[k] = validateAccessor(k);
    for (std::size_t k = 0; k < images_.size(); ++k)
      if (images_[k].bufferView >= 0 && !inRange(images_[k].bufferView, model_.bufferViews.size()))
        error(fmt::format(
            "image {}: {}", k,
            outOfRange("buffer view", images_[k].bufferView, model_.bufferViews.size())));
    for (std::size_t t = 0; t < model_.textures.size(); ++t) {
      const tinygltf::Texture& g = model_.textures[t];
      if (g.source != -1 && !inRange(g.source, images_.size()))
        error(fmt::format("texture {}: {}", t, outOfRange("image", g.source, images_.size())));
      if (g.sampler != -1 && !inRange(g.sampler, model_.samplers.size()))
        error(fmt::format("texture {}: {}", t,
                          outOfRange("sampler", g.sampler, model_.samplers.size())));
    }
    for (std::size_t k = 0; k < model_.materials.size(); ++k) validateMaterial(k);
    for (std::size_t m = 0; m < model_.meshes.size(); ++m)
      for (std::size_t p = 0; p < model_.meshes[m].primitives.size(); ++p) validatePrimitive(m, p);
    validateNodes();
  }

  void validateBufferViews() {
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

  // Buffer view `v`, which `where` refers to, checked to exist.
  const tinygltf::BufferView& bufferView(const std::string& where, int v) const {
    if (!inRange(v, model_.bufferViews.size()))
      error(where + ": " + outOfRange("buffer view", v, model_.bufferViews.size()));
    return model_.bufferViews[static_cast<std::size_t>(v)];
  }

  // Checks that `count` elements of `size` bytes, `stride` apart, from `offset` fit in view `v`;
  // returns their address.
  const std::uint8_t* viewRange(const std::string& where, int v, u64 offset, u64 count, u64 size,
                                u64 stride) const {
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

  AccessorLayout validateAccessor(std::size_t k) const {
    const tinygltf::Accessor& a = accessors()[k];
    const std::string where = fmt::format("accessor {}", k);
    AccessorLayout l;
    const std::size_t cs = componentSize(a.componentType);
    if (cs == 0)
      error(
          fmt::format("{}: componentType {} is not a glTF component type", where, a.componentType));
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

  void validateMaterial(std::size_t k) {
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

  void validatePrimitive(std::size_t m, std::size_t p) {
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

  static int lightIndexOf(const tinygltf::Node& node) {
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end() || !ext->second.IsObject() || !ext->second.Has("light"))
      return -1;
    const tinygltf::Value& v = ext->second.Get("light");
    return v.IsInt() ? v.Get<int>() : std::numeric_limits<int>::min();
  }

  // Every index a node holds is in range, and the nodes form disjoint trees (glTF 2.0 3.5.1:
  // no node has two parents, no cycles), so the scene is walked once per node.
  void validateNodes() {
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
          error(where + ": KHR_lights_punctual " +
                outOfRange("light", light, model_.lights.size()));
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

  // The rendered scene's nodes in depth-first order (children in order), with their world
  // transforms: the instances of meshes and lights, and the first camera.
  void walkScene() {
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
      sceneIndex_ = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      roots = model_.scenes[static_cast<std::size_t>(sceneIndex_)].nodes;
    } else {
      for (std::size_t n = 0; n < nodes().size(); ++n)
        if (parents_[n] == -1) roots.push_back(static_cast<int>(n));
    }
    inScene_.assign(nodes().size(), false);
    std::vector<std::pair<int, glm::mat4>> stack;
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.emplace_back(*r, glm::mat4(1.0f));
    while (!stack.empty()) {
      const auto [n, parent] = stack.back();
      stack.pop_back();
      const tinygltf::Node& node = nodes()[static_cast<std::size_t>(n)];
      inScene_[static_cast<std::size_t>(n)] = true;
      const glm::mat4 world = parent * nodeTransform(node);
      if (node.camera >= 0 && !camera_) camera_ = std::make_pair(node.camera, world);
      if (node.mesh >= 0) instances_.push_back({n, world});
      if (lightIndexOf(node) >= 0) lightInstances_.push_back({n, world});
      for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
        stack.emplace_back(*c, world);
    }
  }

  // One warning for each extension the file uses that ibl does not render.
  void warnAboutExtensions() {
    for (const std::string& ext : model_.extensionsUsed)
      if (!implemented(ext) && !harmless(ext))
        warn(fmt::format("uses the extension {}, which ibl does not implement", ext),
             "rendering without it");
  }

  // --- 4. Images and materials --------------------------------------------------------------

  struct ImageState {
    bool probed = false, missing = false;
    ImageProbe probe;
    std::string key;  // the same key: the same bytes (decoded once)
  };

  std::string sourceName(int image) const {
    const ImageSource& s = images_[static_cast<std::size_t>(image)];
    if (s.bufferView >= 0) return fmt::format("buffer view {}", s.bufferView);
    if (parseDataUri(s.uri)) return "data URI";
    return s.uri;
  }

  // "texture 'wood.png' (image 2)", "texture image 2 (buffer view 5)"
  std::string imageLabel(int image) const {
    const ImageSource& s = images_[static_cast<std::size_t>(image)];
    if (s.bufferView < 0 && !parseDataUri(s.uri))
      return fmt::format("texture '{}' (image {})", s.uri, image);
    return fmt::format("texture image {} ({})", image, sourceName(image));
  }

  // The image's bytes (empty when missing: `missing` set, or unreadable: `problem` set).
  std::vector<std::uint8_t> ownedBytes_;
  std::span<const std::uint8_t> imageBytes(int image, ImageState& st) {
    const ImageSource& s = images_[static_cast<std::size_t>(image)];
    ownedBytes_.clear();
    if (s.bufferView >= 0) {
      const tinygltf::BufferView& bv = model_.bufferViews[static_cast<std::size_t>(s.bufferView)];
      st.key = fmt::format("view {} {} {}", bv.buffer, bv.byteOffset, bv.byteLength);
      return {model_.buffers[static_cast<std::size_t>(bv.buffer)].data.data() + bv.byteOffset,
              bv.byteLength};
    }
    if (const auto data = parseDataUri(s.uri)) {
      st.key = fmt::format("image {}", image);
      std::optional<std::vector<std::uint8_t>> bytes;
      if (data->base64) bytes = decodeBase64(data->payload);
      if (!bytes) {
        st.probe.problem = "a data URI that is not base64";
        return {};
      }
      ownedBytes_ = std::move(*bytes);
      return ownedBytes_;
    }
    const fs::path file = fs::path(path_).parent_path() / percentDecode(s.uri);
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) {
      st.missing = true;
      return {};
    }
    const fs::path canonical = fs::weakly_canonical(file, ec);
    st.key = "file " + (ec ? file : canonical).string();
    try {
      ownedBytes_ = readFileBytes(file);
    } catch (const Error& e) {
      st.probe.problem = e.what();
      return {};
    }
    return ownedBytes_;
  }

  std::map<int, ImageState> imageStates_;
  const ImageState& imageState(int image) {
    ImageState& st = imageStates_[image];
    if (!st.probed) {
      st.probed = true;
      const std::span<const std::uint8_t> bytes = imageBytes(image, st);
      if (!st.missing && st.probe.problem.empty()) st.probe = probeImage(bytes);
    }
    return st;
  }

  std::string noSourceProblem(int texture) const {
    const tinygltf::Texture& g = model_.textures[static_cast<std::size_t>(texture)];
    std::string others;
    for (const auto& [name, value] : g.extensions) others += (others.empty() ? "" : ", ") + name;
    return others.empty() ? "no image" : "no PNG or JPEG image (only " + others + ")";
  }

  // The textures, one per glTF texture; those the materials read decoded (with `decode`) or
  // only checked. A missing or unreadable image is a warning and its textures are empty.
  std::vector<Texture> readTextures(bool decode) {
    std::map<int, std::shared_ptr<const std::vector<std::uint8_t>>> decoded;
    std::map<std::string, std::shared_ptr<const std::vector<std::uint8_t>>> byKey;
    u64 texelBytes = 0;
    DisjointRanges views;  // of the images decoded from buffer views
    std::set<int> warned;
    std::vector<Texture> textures;
    for (std::size_t t = 0; t < model_.textures.size(); ++t) {
      const tinygltf::Texture& g = model_.textures[t];
      Texture tex;
      tex.sampler = samplerOf(g.sampler);
      const bool used = usedTextures_.count(static_cast<int>(t)) > 0;
      if (used && g.source < 0) {
        warn(fmt::format("texture {} has {}", t, noSourceProblem(static_cast<int>(t))),
             "rendering without it");
      } else if (used) {
        const int k = g.source;
        const ImageState& st = imageState(k);
        if (st.missing || !st.probe.problem.empty()) {
          if (warned.insert(k).second)
            warn(st.missing ? imageLabel(k) + " is missing"
                            : fmt::format("{} is {}", imageLabel(k), st.probe.problem),
                 "rendering without it");
        } else if (decode) {
          auto& rgba = decoded[k];
          if (!rgba) {
            auto& shared = byKey[st.key];
            if (!shared) {
              ImageState scratch;
              const std::span<const std::uint8_t> bytes = imageBytes(k, scratch);
              if (const int v = images_[static_cast<std::size_t>(k)].bufferView; v >= 0) {
                const tinygltf::BufferView& bv = model_.bufferViews[static_cast<std::size_t>(v)];
                if (!views.add(bv.buffer, bv.byteOffset, bv.byteOffset + bv.byteLength))
                  error(fmt::format("{}: the images' buffer views overlap", imageLabel(k)));
              }
              texelBytes += 4 * static_cast<u64>(st.probe.width) * st.probe.height;
              if (texelBytes > options_.maxTextureBytes)
                error(fmt::format("its textures decode to more than {} (the limit)",
                                  formatBytes(options_.maxTextureBytes)));
              shared = decodeImage(k, bytes, st.probe);
            }
            rgba = shared;
          }
          if (rgba && !rgba->empty()) {
            tex.width = st.probe.width;
            tex.height = st.probe.height;
            tex.rgba = rgba;
          }
        }
      }
      textures.push_back(std::move(tex));
    }
    return textures;
  }

  // The image decoded to 8-bit RGBA; empty (and a warning) if the decoder fails.
  std::shared_ptr<const std::vector<std::uint8_t>> decodeImage(int image,
                                                               std::span<const std::uint8_t> bytes,
                                                               const ImageProbe& probe) {
    int w = 0, h = 0, comp = 0;
    unsigned char* px =
        stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &comp, 4);
    if (!px || w != probe.width || h != probe.height) {
      const std::string reason = px ? "its size changed while decoding" : stbi_failure_reason();
      stbi_image_free(px);
      warn(fmt::format("{} cannot be decoded ({})", imageLabel(image), reason),
           "rendering without it");
      return std::make_shared<const std::vector<std::uint8_t>>();
    }
    auto out = std::make_shared<std::vector<std::uint8_t>>(
        px, px + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
    stbi_image_free(px);
    return out;
  }

  TextureSampler samplerOf(int index) const {
    TextureSampler s;
    if (index < 0) return s;
    const tinygltf::Sampler& g = model_.samplers[static_cast<std::size_t>(index)];
    s.wrapS = wrapOf(g.wrapS);
    s.wrapT = wrapOf(g.wrapT);
    s.nearest = g.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
    s.mipmaps = g.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST &&
                g.minFilter != TINYGLTF_TEXTURE_FILTER_LINEAR;
    return s;
  }

  static glm::vec3 emissiveOf(const tinygltf::Material& m) {
    glm::vec3 e(0.0f);
    if (m.emissiveFactor.size() == 3)
      e = glm::vec3(static_cast<float>(m.emissiveFactor[0]),
                    static_cast<float>(m.emissiveFactor[1]),
                    static_cast<float>(m.emissiveFactor[2]));
    // KHR_materials_emissive_strength: a scale of the emission past 1 (physical units).
    const auto strength = m.extensions.find("KHR_materials_emissive_strength");
    if (strength != m.extensions.end() && strength->second.IsObject() &&
        strength->second.Has("emissiveStrength") &&
        strength->second.Get("emissiveStrength").IsNumber())
      e *= static_cast<float>(strength->second.Get("emissiveStrength").GetNumberAsDouble());
    return e;
  }

  // The metallic-roughness materials, then a default one (gray, roughness 0.5) for primitives
  // without a material; textures are indices into readTextures' list, -1 for none.
  std::vector<Material> readMaterials(const std::vector<Texture>& textures) {
    std::vector<Material> materials;
    for (std::size_t k = 0; k < model_.materials.size(); ++k) {
      const tinygltf::Material& m = model_.materials[k];
      std::map<std::string, TextureRef> refs;
      for (const SlotRef& slot : materialSlots(m, path_, materialLabel(k))) {
        TextureRef ref;
        if (slot.index >= 0 && slot.texCoord > 1) {
          warn(fmt::format("material {}: {} reads TEXCOORD_{}, which ibl does not read", k,
                           slot.name, slot.texCoord),
               "rendering without that texture");
        } else if (slot.index >= 0 && !textures[static_cast<std::size_t>(slot.index)].empty()) {
          ref.index = slot.index;
          ref.texCoord = slot.texCoord;
        }
        refs[slot.name] = ref;
      }
      Material mat;
      const auto& pbr = m.pbrMetallicRoughness;
      mat.baseColor = glm::vec3(static_cast<float>(pbr.baseColorFactor[0]),
                                static_cast<float>(pbr.baseColorFactor[1]),
                                static_cast<float>(pbr.baseColorFactor[2]));
      mat.baseColorTexture = refs["baseColorTexture"];
      mat.baseColorAlpha = static_cast<float>(pbr.baseColorFactor[3]);
      mat.alphaMode = m.alphaMode == "MASK"    ? AlphaMode::Mask
                      : m.alphaMode == "BLEND" ? AlphaMode::Blend
                                               : AlphaMode::Opaque;
      mat.alphaCutoff = static_cast<float>(m.alphaCutoff);
      mat.metallic = static_cast<float>(pbr.metallicFactor);
      mat.roughness = static_cast<float>(pbr.roughnessFactor);
      mat.metallicRoughnessTexture = refs["metallicRoughnessTexture"];
      mat.normalTexture = refs["normalTexture"];
      mat.normalScale = static_cast<float>(m.normalTexture.scale);
      mat.occlusionTexture = refs["occlusionTexture"];
      mat.occlusionStrength = static_cast<float>(m.occlusionTexture.strength);
      mat.emissive = emissiveOf(m);
      mat.emissiveTexture = refs["emissiveTexture"];
      // KHR_materials_sheen: sheenColorFactor (default 0: no sheen), sheenRoughnessFactor
      // (default 0), and their textures (color in RGB, sRGB; roughness in A).
      const auto sheen = m.extensions.find("KHR_materials_sheen");
      if (sheen != m.extensions.end() && sheen->second.IsObject()) {
        const tinygltf::Value& x = sheen->second;
        if (x.Has("sheenColorFactor") && x.Get("sheenColorFactor").ArrayLen() == 3)
          for (int c = 0; c < 3; ++c)
            mat.sheenColor[c] = static_cast<float>(
                x.Get("sheenColorFactor").Get(static_cast<std::size_t>(c)).GetNumberAsDouble());
        if (x.Has("sheenRoughnessFactor"))
          mat.sheenRoughness =
              static_cast<float>(x.Get("sheenRoughnessFactor").GetNumberAsDouble());
        mat.sheenColorTexture = refs["sheenColorTexture"];
        mat.sheenRoughnessTexture = refs["sheenRoughnessTexture"];
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

  // --- 5. Geometry --------------------------------------------------------------------------

  // Bytes per vertex and per index as a Scene stores them: position, normal, tangent, two UV
  // sets; one 32-bit index.
  static constexpr u64 kVertexBytes = 12 + 12 + 16 + 8 + 8, kIndexBytes = 4;
  // Draco's peak while decoding, per triangle its stream declares: the edgebreaker's corner table
  // (24 bytes, measured), its other tables, the attributes' values (up to 3 points a triangle) and
  // the copy into the Scene.
  static constexpr u64 kDracoBytesPerFace = 128;

  std::string primitiveLabel(int m, std::size_t p) const {
    return fmt::format("mesh {} primitive {}", m, p);
  }

  // The primitive's data (null for what is not a triangle list), read by prepareGeometry.
  PrimitiveData* primitive(int m, std::size_t p) {
    auto& prims = primitives_[static_cast<std::size_t>(m)];
    return p < prims.size() && prims[p] ? &*prims[p] : nullptr;
  }

  // Sizes each triangle primitive of the meshes with uses[m] > 0 (Draco ones by decoding them),
  // refuses a scene larger than the limit (every use counted), then reads them.
  void prepareGeometry(const std::vector<std::size_t>& uses) {
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
      data.bytes =
          kIndexBytes * data.mesh.indices.size() + kVertexBytes * data.mesh.positions.size();
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

  int attributeOf(const tinygltf::Primitive& prim, const char* name) const {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  }

  // The bytes a primitive takes in the Scene, at most: its indices, and as many vertices as
  // it has or as its indices name, whichever is fewer.
  u64 estimatePrimitive(int m, std::size_t p) const {
    const tinygltf::Primitive& prim = model_.meshes[static_cast<std::size_t>(m)].primitives[p];
    const int position = attributeOf(prim, "POSITION");
    if (position < 0) error(primitiveLabel(m, p) + " has no POSITION");
    const u64 vertices = layouts_[static_cast<std::size_t>(position)].count;
    const u64 indices =
        prim.indices >= 0 ? layouts_[static_cast<std::size_t>(prim.indices)].count : vertices;
    return saturatingAdd(saturatingMul(kIndexBytes, indices),
                         saturatingMul(kVertexBytes, std::min(vertices, indices)));
  }

  // Checks an attribute accessor: its type, a component type glTF allows for attributes, and
  // one value per vertex.
  const AccessorLayout& attribute(int m, std::size_t p, const char* name, int accessor,
                                  int components, std::size_t vertices) const {
    const AccessorLayout& a = layouts_[static_cast<std::size_t>(accessor)];
    const std::string where =
        fmt::format("{}: {} accessor {}", primitiveLabel(m, p), name, accessor);
    if (a.components != components || a.matrix)
      error(fmt::format("{} is {}, not {}", where, typeName(a.components), typeName(components)));
    if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      error(where + " has 32-bit integer components, which glTF does not allow for attributes");
    if (vertices != kU64Max && a.count != vertices)
      error(fmt::format("{} has {} values for {} positions", where, a.count, vertices));
    return a;
  }

  // A primitive from its accessors: the indices (checked against the vertex count), the
  // vertices they use (in their order), each attribute's values of those vertices.
  Mesh readPrimitive(int m, std::size_t p) const {
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
          error(fmt::format("{}: index {} is vertex {}, out of range (POSITION has {})", where, i,
                            v, vertices));
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
    return mesh;
  }

  // Renumbers `indices` to the vertices they use, in the vertices' order; returns the old
  // numbers of the vertices kept. Memory in proportion to the indices, not to `vertices`.
  static std::vector<std::uint32_t> keepUsed(std::vector<std::uint32_t>& indices,
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
        i = static_cast<std::uint32_t>(std::lower_bound(kept.begin(), kept.end(), i) -
                                       kept.begin());
    }
    return kept;
  }

  // The bytes of a KHR_draco_mesh_compression primitive's stream.
  std::span<const std::uint8_t> dracoBytes(int m, std::size_t p) const {
    const tinygltf::Primitive& prim = model_.meshes[static_cast<std::size_t>(m)].primitives[p];
    const tinygltf::Value& ext = prim.extensions.at("KHR_draco_mesh_compression");
    const int view = *extensionIndex(ext, "bufferView", path_, primitiveLabel(m, p));
    const tinygltf::BufferView& bv = model_.bufferViews[static_cast<std::size_t>(view)];
    return {model_.buffers[static_cast<std::size_t>(bv.buffer)].data.data() + bv.byteOffset,
            bv.byteLength};
  }

  // A KHR_draco_mesh_compression primitive: attributes and triangles from the Draco stream.
  Mesh readDracoPrimitive(int m, std::size_t p) const {
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
    const auto read = [&](const char* name, int n, auto& out) {
      if (!attributes.Has(name)) return;
      const draco::PointAttribute* att = dm->GetAttributeByUniqueId(static_cast<std::uint32_t>(
          *extensionIndex(attributes, name, path_, where + " attributes")));
      if (!att) error(fmt::format("{}: the stream has no {} attribute", where, name));
      out.resize(kept.size());
      for (std::size_t i = 0; i < kept.size(); ++i) {
        float v[4] = {0, 0, 0, 0};
        att->ConvertValue<float>(att->mapped_index(draco::PointIndex(kept[i])),
                                 static_cast<std::int8_t>(n), v);
        for (int c = 0; c < n; ++c) out[i][c] = v[c];
      }
    };
    if (!attributes.Has("POSITION")) error(where + " has no POSITION");
    read("POSITION", 3, mesh.positions);
    read("NORMAL", 3, mesh.normals);
    read("TEXCOORD_0", 2, mesh.uvs);
    read("TANGENT", 4, mesh.tangents);
    read("TEXCOORD_1", 2, mesh.uvs1);
    return mesh;
  }

  // Positions past float range (a transform's scale, or values of 3e38) would break the bounds
  // and the ray tracer.
  void checkFinite(const Mesh& mesh, int m, std::size_t p, int node) const {
    for (const glm::vec3& v : mesh.positions)
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        error(fmt::format("{} (node {}): a vertex lies at a non-finite position",
                          primitiveLabel(m, p), node));
  }

  // KHR_lights_punctual: a node's light shines down the node's -Z from its origin, in the
  // extension's units (cd for point and spot, lx for directional).
  Light lightOf(const Instance& instance) const {
    const int i = lightIndexOf(nodes()[static_cast<std::size_t>(instance.node)]);
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
    light.position = glm::vec3(instance.world[3]);
    const glm::vec3 forward = -glm::vec3(instance.world[2]);
    if (!(glm::length(forward) > 0.0f)) fail(light.name, "the node's transform is degenerate");
    // A directional light's direction is toward the sun, against where it shines.
    light.direction = glm::normalize(light.type == LightType::Sun ? -forward : forward);
    checkLight(light);
    return light;
  }

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
};

// Runs `body`, turning what a hostile file could still make escape (an allocation the checks
// did not foresee, a library's exception) into an Error naming the file.
template <typename F>
auto guarded(const std::string& path, F&& body) -> decltype(body()) {
  try {
    return body();
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    fail(path, "out of memory while reading it");
  } catch (const std::length_error&) {
    fail(path, "out of memory while reading it");
  } catch (const std::exception& e) {
    fail(path, fmt::format("cannot be read: {}", firstLine(e.what())));
  }
}

}  // namespace

Scene loadGltf(std::span<const std::uint8_t> bytes, const std::string& path,
               const GltfLoadOptions& options) {
  return guarded(path, [&] { return GltfDocument(bytes, path, options).load(); });
}

Scene loadGltf(const std::string& path, const GltfLoadOptions& options) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  return loadGltf(bytes, path, options);
}

GltfSummary describeGltf(std::span<const std::uint8_t> bytes, const std::string& path,
                         const GltfLoadOptions& options) {
  return guarded(path, [&] { return GltfDocument(bytes, path, options).describe(); });
}

GltfSummary describeGltf(const std::string& path, const GltfLoadOptions& options) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  return describeGltf(bytes, path, options);
}

}  // namespace ibl
