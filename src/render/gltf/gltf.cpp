// The public API of include/ibl/render/gltf.hpp: GltfDocument (document.hpp) read and checked,
// then loaded or described, with what could still escape from a hostile file made an Error.
#include "ibl/render/gltf.hpp"

#include <exception>
#include <new>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "document.hpp"
#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"

namespace ibl {

namespace gltf {

GltfDocument::GltfDocument(std::span<const std::uint8_t> bytes, const std::string& path,
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

void GltfDocument::warn(const std::string& problem, const std::string& instead) {
  if (options_.strict) fail(path_, problem);
  warnings_.push_back(problem + "; " + instead);
  if (options_.warn) options_.warn(path_ + ": " + warnings_.back());
}

namespace {

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

}  // namespace gltf

Scene loadGltf(std::span<const std::uint8_t> bytes, const std::string& path,
               const GltfLoadOptions& options) {
  return gltf::guarded(path, [&] { return gltf::GltfDocument(bytes, path, options).load(); });
}

Scene loadGltf(const std::string& path, const GltfLoadOptions& options) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  return loadGltf(bytes, path, options);
}

GltfSummary describeGltf(std::span<const std::uint8_t> bytes, const std::string& path,
                         const GltfLoadOptions& options) {
  return gltf::guarded(path, [&] { return gltf::GltfDocument(bytes, path, options).describe(); });
}

GltfSummary describeGltf(const std::string& path, const GltfLoadOptions& options) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  return describeGltf(bytes, path, options);
}

}  // namespace ibl
