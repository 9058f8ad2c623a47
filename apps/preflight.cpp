#include "preflight.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>

#include <fmt/core.h>

#include "ibl/core/error.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/io/file_io.hpp"

namespace ibl::cli {

namespace fs = std::filesystem;

std::vector<fs::path> filesOfInput(const std::string& input) {
  if (input.empty() || isSkySpec(input)) return {};
  if (input.find("{face}") == std::string::npos) return {input};
  std::vector<fs::path> faces;
  for (int f = 0; f < kFaceCount; ++f) faces.push_back(facePath(input, f));
  return faces;
}

void requireReadable(const std::string& input) {
  if (isSkySpec(input)) {
    parseSkySpec(input);
    return;
  }
  for (const fs::path& file : filesOfInput(input)) {
    std::error_code ec;
    const fs::file_status status = fs::status(file, ec);
    if (!fs::exists(status)) fail(file.string(), "no such file");
    if (fs::is_directory(status)) fail(file.string(), "is a directory, not a file");
    if (::access(file.c_str(), R_OK) != 0)
      fail(file.string(), fmt::format("cannot be read: {}", std::strerror(errno)));
  }
}

namespace {

// Whether two paths name the same existing file (false when either does not exist).
bool sameFile(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  const bool same = fs::equivalent(a, b, ec);
  return !ec && same;
}

// `path` with links, "." and ".." resolved as far as it exists.
fs::path resolved(const fs::path& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? fs::absolute(path).lexically_normal() : p;
}

// Whether `out` names the file `in`: as the system resolves it, or with ".." taken lexically
// first (through a folder that does not exist yet, "new/../in.exr" is in.exr once the folder
// is created).
bool namesTheSameFile(const fs::path& out, const fs::path& in) {
  std::error_code ec;
  const fs::path lexical = fs::absolute(out, ec).lexically_normal();
  return sameFile(out, in) || sameFile(lexical, in) || resolved(out) == resolved(in) ||
         resolved(lexical) == resolved(in);
}

}  // namespace

void refuseOverwritingInputs(const std::vector<fs::path>& outputs,
                             const std::vector<fs::path>& inputs) {
  for (const fs::path& out : outputs)
    for (const fs::path& in : inputs)
      if (namesTheSameFile(out, in))
        failUsage(out.string(), fmt::format("is the input {}: writing it would destroy the input; "
                                            "choose another output",
                                            in.string()));
}

void requireWritableFile(const fs::path& output) {
  const std::string name = output.string();
  std::error_code ec;
  if (fs::is_directory(output, ec)) fail(name, "is a directory; name a file to write");
  // The folders the write would create, up to the nearest one that exists (writeFileAtomic
  // creates them, as a bake its directory).
  fs::path folder = output.lexically_normal().parent_path();
  while (!folder.empty() && !fs::exists(folder, ec) && folder != folder.root_path())
    folder = folder.parent_path();
  if (folder.empty()) folder = ".";
  if (!fs::is_directory(folder, ec))
    fail(name, fmt::format("cannot be written: {} is not a directory", folder.string()));
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    fail(name, fmt::format("cannot be written in {}: {}", folder.string(), std::strerror(errno)));
}

void refuseInputsInside(const fs::path& outDir, const std::vector<fs::path>& inputs) {
  const fs::path dir = resolved(outDir);
  for (const fs::path& in : inputs) {
    const fs::path file = resolved(in);
    const fs::path rel = file.lexically_relative(dir);
    if (sameFile(in, outDir) || (!rel.empty() && *rel.begin() != ".."))
      failUsage(outDir.string(),
                fmt::format("holds the input {}, which writing this output directory may replace "
                            "or remove; write elsewhere or move the input",
                            in.string()));
  }
}

namespace {

// A number from a /proc or /sys file ("max" or unreadable: none).
std::optional<std::uint64_t> readNumber(const char* file, const char* key = nullptr) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  std::string word;
  if (!key) {
    in >> word;
    try {
      return std::stoull(word);
    } catch (const std::exception&) {
      return std::nullopt;
    }
  }
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) {
      try {
        return std::stoull(line.substr(std::strlen(key))) * 1024;  // "kB"
      } catch (const std::exception&) {
        return std::nullopt;
      }
    }
  return std::nullopt;
}

}  // namespace

std::uint64_t availableMemoryBytes() {
  if (const char* limit = std::getenv("IBL_MEMORY_LIMIT")) return std::strtoull(limit, nullptr, 10);
  std::uint64_t available = readNumber("/proc/meminfo", "MemAvailable:").value_or(UINT64_MAX);
  const auto cgroupMax = readNumber("/sys/fs/cgroup/memory.max");
  const auto cgroupUsed = readNumber("/sys/fs/cgroup/memory.current");
  if (cgroupMax && cgroupUsed)
    available = std::min(available, *cgroupMax > *cgroupUsed ? *cgroupMax - *cgroupUsed : 0);
  return available;
}

std::string formatBytes(double bytes) {
  if (bytes >= 1e9) return fmt::format("{:.1f} GB", bytes / 1e9);
  if (bytes >= 1e6) return fmt::format("{:.0f} MB", bytes / 1e6);
  return fmt::format("{:.0f} kB", std::max(bytes / 1e3, 1.0));
}

void requireMemory(std::uint64_t bytes, std::string_view job, std::string_view hint) {
  const std::uint64_t available = availableMemoryBytes();
  if (bytes <= available) return;
  fail(job,
       fmt::format(
           "needs about {} of memory, more than the {} {}; {}",
           formatBytes(static_cast<double>(bytes)), formatBytes(static_cast<double>(available)),
           std::getenv("IBL_MEMORY_LIMIT") ? "IBL_MEMORY_LIMIT allows" : "this machine has free",
           hint));
}

void requireDiskSpace(const fs::path& where, std::uint64_t bytes, std::string_view job) {
  const std::optional<std::uint64_t> free = freeDiskBytes(where);
  if (free && bytes > *free)
    fail(where.string(), fmt::format("{} needs about {} of disk space; the disk has {} free", job,
                                     formatBytes(static_cast<double>(bytes)),
                                     formatBytes(static_cast<double>(*free))));
}

}  // namespace ibl::cli
