#include "json_filter.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common.hpp"
#include "ibl/core/error.hpp"
#include "ibl/io/json_file.hpp"
#include "io/text_codecs.hpp"

namespace ibl::gltf {

namespace {

namespace fs = std::filesystem;

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

// Whether the member `key` holds a texture info (a material's slot: "normalTexture",
// "clearcoatTexture", ...).
bool textureInfo(const std::string& key) {
  return key.ends_with("Texture");
}

// Whether ibl reads the extension `name` on an object of `kind` (the key of the array or object
// holding it; "" for the file's root). EXT_meshopt_compression is read by hideMeshoptFallbacks.
bool readsExtension(const std::string& kind, const std::string& name) {
  return (kind.empty() && (name == "KHR_lights_punctual" || name == "KHR_materials_variants")) ||
         (kind == "nodes" && name == "KHR_lights_punctual") ||
         (kind == "primitives" && name == "KHR_materials_variants") ||
         (kind == "materials" &&
          (name == "KHR_materials_sheen" || name == "KHR_materials_emissive_strength" ||
           name == "KHR_materials_ior" || name == "KHR_materials_specular" ||
           name == "KHR_materials_unlit" || name == "KHR_materials_clearcoat" ||
           name == "KHR_materials_iridescence" || name == "KHR_materials_anisotropy" ||
           name == "KHR_materials_transmission" || name == "KHR_materials_volume")) ||
         (kind == "primitives" && name == "KHR_draco_mesh_compression") ||
         (kind == "textures" && name == "EXT_texture_webp") ||
         (textureInfo(kind) && name == "KHR_texture_transform") ||
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
      // The lights of a file: 16 values at most each (type, color, intensity, range, spot, name);
      // the variants' names, and a primitive's mappings (a material and the variants it is in).
      const nlohmann::json* list = !kind.empty() ? nullptr
                                   : name == "KHR_lights_punctual"
                                       ? member(ext.value(), "lights")
                                       : member(ext.value(), "variants");
      if (kind == "primitives" && name == "KHR_materials_variants")
        list = member(ext.value(), "mappings");
      const std::size_t perEntry = name == "KHR_lights_punctual" ? 64 : 256;
      const std::size_t limit =
          list && list->is_array() ? perEntry * (list->size() + 1) : std::size_t{256};
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
  // A texture info's extensions: keys[d - 3] is the slot.
  if (d >= 4 && textureInfo(keys[d - 3])) return readsExtension(keys[d - 3], keys[d - 1]);
  return readsExtension(d == 3 ? "" : d >= 5 ? keys[d - 4] : "-", keys[d - 1]);
}

}  // namespace

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

}  // namespace ibl::gltf
