#include "ibl/io/file_io.hpp"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>

#include <fmt/format.h>
#include <unistd.h>

#include "ibl/core/error.hpp"

namespace ibl {

namespace fs = std::filesystem;

std::vector<std::uint8_t> readFileBytes(const fs::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (ec || !fs::exists(status)) fail(name, "no such file");
  if (fs::is_directory(status)) fail(name, "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(name, fmt::format("cannot open: {}", std::strerror(errno)));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) fail(name, "cannot determine the file size");
  if (static_cast<std::uint64_t>(size) > kMaxFileBytes)
    fail(name, fmt::format("file of {} bytes exceeds the {} byte limit", size, kMaxFileBytes));
  in.seekg(0);
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size)) fail(name, "read error");
  return bytes;
}

namespace {

// A new name beside `path` that no other write of this process uses: PATH.<pid>.<n>.<tag>.
fs::path besides(const fs::path& path, const char* tag) {
  static std::atomic<unsigned> counter{0};
  fs::path p = path;
  p += fmt::format(".{}.{}.{}", static_cast<long>(::getpid()), counter++, tag);
  return p;
}

// Writes `bytes` to the new file `tmp` (creating the parent directories of `path`); errors
// name `path`, the user's file.
void writeNewFile(const fs::path& path, const fs::path& tmp, std::span<const std::uint8_t> bytes) {
  const std::string name = path.string();
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) fail(name, fmt::format("cannot create directory: {}", ec.message()));
  }
  if (fs::is_directory(path, ec)) fail(name, "is a directory");
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) fail(name, fmt::format("cannot write: {}", std::strerror(errno)));
  const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  const bool closed = std::fclose(f) == 0;
  if (!ok || !closed) {
    fs::remove(tmp, ec);
    fail(name, "write failed (disk full or file too large?)");
  }
}

}  // namespace

void writeFileAtomic(const fs::path& path, std::span<const std::uint8_t> bytes) {
  const fs::path tmp = besides(path, "tmp");
  writeNewFile(path, tmp, bytes);
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    fail(path.string(), fmt::format("cannot rename into place: {}", ec.message()));
  }
}

void writeFilesTogether(std::span<const EncodedFile> files) {
  std::vector<fs::path> temps;
  std::error_code ignored;
  try {
    for (const EncodedFile& f : files) {
      temps.push_back(besides(f.path, "tmp"));
      writeNewFile(f.path, temps.back(), f.bytes);
    }
  } catch (...) {
    for (const auto& t : temps) fs::remove(t, ignored);
    throw;
  }
  // Every file is complete: move them into place, keeping what they replace until the end.
  std::vector<std::pair<fs::path, fs::path>> replaced;  // (destination, kept aside as)
  std::size_t placed = 0;
  for (; placed < files.size(); ++placed) {
    const fs::path& dest = files[placed].path;
    std::error_code ec;
    if (fs::exists(dest, ec)) {
      const fs::path aside = besides(dest, "old");
      fs::rename(dest, aside, ec);
      if (!ec) replaced.emplace_back(dest, aside);
    }
    if (!ec) fs::rename(temps[placed], dest, ec);
    if (ec) {  // roll back: remove what was placed, restore what it replaced
      for (std::size_t i = 0; i < placed; ++i) fs::remove(files[i].path, ignored);
      for (const auto& [d, aside] : replaced) fs::rename(aside, d, ignored);
      for (std::size_t i = placed; i < temps.size(); ++i) fs::remove(temps[i], ignored);
      fail(dest.string(), fmt::format("cannot rename into place: {}", ec.message()));
    }
  }
  for (const auto& [d, aside] : replaced) fs::remove(aside, ignored);
}

}  // namespace ibl
