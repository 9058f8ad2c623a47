#pragma once
// Internal to the glTF loader: the JSON filter that runs before tinygltf parses. It checks the
// JSON's depth and the buffers' sizes, hides what Debian's tinygltf cannot read (Draco
// accessors, EXT_meshopt_compression's fallback buffers), takes the images out (ibl reads them
// itself) and drops what ibl does not read (extras, unread extensions) as it parses.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ibl::gltf {

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

// Checks and prepares a glTF file's JSON for tinygltf.
// @param text     the JSON text (of a .gltf, or a GLB's JSON chunk).
// @param path     the file, for messages.
// @param baseDir  where the file's external buffers are looked for.
// @param binSize  the size of the GLB's BIN chunk; nullopt for a .gltf.
// @return the filtered JSON text, the images and the meshopt views taken out of it. Throws
//         Error("<path>: ...") for JSON it cannot read or whose buffers do not hold their data.
PreparedJson prepareJson(std::string_view text, const std::string& path,
                         const std::filesystem::path& baseDir, std::optional<std::size_t> binSize);

}  // namespace ibl::gltf
