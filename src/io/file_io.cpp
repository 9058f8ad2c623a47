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

void writeFileAtomic(const fs::path& path, std::span<const std::uint8_t> bytes) {
  const std::string name = path.string();
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) fail(name, fmt::format("cannot create directory: {}", ec.message()));
  }
  static std::atomic<unsigned> counter{0};
  fs::path tmp = path;
  tmp += fmt::format(".{}.{}.tmp", static_cast<long>(::getpid()), counter++);
  {
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) fail(name, fmt::format("cannot write: {}", std::strerror(errno)));
    const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    const bool closed = std::fclose(f) == 0;
    if (!ok || !closed) {
      fs::remove(tmp, ec);
      fail(name, "write failed (disk full?)");
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    fail(name, fmt::format("cannot rename into place: {}", ec.message()));
  }
}

}  // namespace ibl
