#include "ibl/io/file_io.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <mutex>
#include <optional>
#include <regex>
#include <set>
#include <system_error>

#include <fmt/format.h>
#include <sys/statvfs.h>
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

// The temporaries of this process that exist now: files, and staging directories. `mutex` is
// held through a rename phase, so that no file is ever kept aside outside it.
struct Registry {
  std::mutex mutex;
  std::set<fs::path> files, directories;
};
Registry& registry() {
  static Registry* r = new Registry;  // never destroyed: an interrupt may come at exit
  return *r;
}

// A new name beside `path` that no other write of this process uses: PATH.<pid>.<n>.<tag>,
// registered until release().
fs::path besides(const fs::path& path, const char* tag) {
  static std::atomic<unsigned> counter{0};
  fs::path p = path;
  p += fmt::format(".{}.{}.{}", static_cast<long>(::getpid()), counter++, tag);
  const std::lock_guard lock(registry().mutex);
  registry().files.insert(p);
  return p;
}

void release(const fs::path& p) {
  const std::lock_guard lock(registry().mutex);
  registry().files.erase(p);
}

// Removes the temporary `p` and forgets it.
void discard(const fs::path& p) {
  std::error_code ignored;
  fs::remove(p, ignored);
  release(p);
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
    discard(tmp);
    fail(name, "write failed (disk full or file too large?)");
  }
}

}  // namespace

void writeFileAtomic(const fs::path& path, std::span<const std::uint8_t> bytes) {
  const fs::path tmp = besides(path, "tmp");
  writeNewFile(path, tmp, bytes);
  std::error_code ec;
  {
    const std::lock_guard lock(registry().mutex);
    fs::rename(tmp, path, ec);
    if (!ec) registry().files.erase(tmp);
  }
  if (ec) {
    discard(tmp);
    fail(path.string(), fmt::format("cannot rename into place: {}", ec.message()));
  }
}

void writeFilesTogether(std::span<const EncodedFile> files) {
  std::vector<fs::path> temps;
  try {
    for (const EncodedFile& f : files) {
      temps.push_back(besides(f.path, "tmp"));
      writeNewFile(f.path, temps.back(), f.bytes);
    }
  } catch (...) {
    for (const auto& t : temps) discard(t);
    throw;
  }
  // Every file is complete: move them into place, keeping what they replace until the end. An
  // interrupt waits for this phase to end (removeTemporariesOfThisProcess takes the lock).
  Registry& reg = registry();
  const std::lock_guard lock(reg.mutex);
  std::error_code ignored;
  std::vector<std::pair<fs::path, fs::path>> replaced;  // (destination, kept aside as)
  std::size_t placed = 0;
  for (; placed < files.size(); ++placed) {
    const fs::path& dest = files[placed].path;
    std::error_code ec;
    if (fs::exists(dest, ec)) {
      fs::path aside = dest;
      aside += fmt::format(".{}.{}.old", static_cast<long>(::getpid()), placed);
      fs::rename(dest, aside, ec);
      if (!ec) replaced.emplace_back(dest, aside);
    }
    if (!ec) fs::rename(temps[placed], dest, ec);
    if (ec) {  // roll back: remove what was placed, restore what it replaced
      for (std::size_t i = 0; i < placed; ++i) fs::remove(files[i].path, ignored);
      for (const auto& [d, aside] : replaced) fs::rename(aside, d, ignored);
      for (std::size_t i = placed; i < temps.size(); ++i) fs::remove(temps[i], ignored);
      for (const auto& t : temps) reg.files.erase(t);
      fail(dest.string(), fmt::format("cannot rename into place: {}", ec.message()));
    }
  }
  for (const auto& [d, aside] : replaced) fs::remove(aside, ignored);
  for (const auto& t : temps) reg.files.erase(t);
}

std::optional<std::uint64_t> freeDiskBytes(const fs::path& where) {
  std::error_code ec;
  fs::path dir = fs::absolute(where, ec).lexically_normal();
  while (!dir.empty() && !fs::is_directory(dir, ec) && dir != dir.root_path())
    dir = dir.parent_path();
  struct statvfs s {};
  if (dir.empty() || ::statvfs(dir.c_str(), &s) != 0) return std::nullopt;
  return static_cast<std::uint64_t>(s.f_bavail) * s.f_frsize;
}

StagingDirectory::StagingDirectory(fs::path dir) : dir_(std::move(dir)) {
  const std::lock_guard lock(registry().mutex);
  registry().directories.insert(dir_);
}

StagingDirectory::~StagingDirectory() {
  const std::lock_guard lock(registry().mutex);
  registry().directories.erase(dir_);
}

fs::path stagingDirectoryFor(const fs::path& outDir, long pid) {
  const fs::path parent = outDir.has_parent_path() ? outDir.parent_path() : fs::path(".");
  std::string name = outDir.filename().string();
  if (name.empty()) name = outDir.parent_path().filename().string();  // "dir/"
  return parent / fmt::format(".{}.ibl-staging-{}", name, pid);
}

void removeTemporariesOfThisProcess() {
  Registry& reg = registry();
  const std::lock_guard lock(reg.mutex);  // after a rename phase in progress
  std::error_code ignored;
  for (const auto& f : reg.files) fs::remove(f, ignored);
  for (const auto& d : reg.directories) fs::remove_all(d, ignored);
  reg.files.clear();
  reg.directories.clear();
}

namespace {

// Whether process `pid` runs (or may: one we cannot signal is someone else's, and alive).
bool processAlive(long pid) {
  if (pid <= 0) return false;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

// The pid in a temporary's name "<file>.<pid>.<n>.tmp" or ".old", with the destination; none
// for other names.
std::optional<std::pair<long, fs::path>> temporaryOwner(const fs::path& p) {
  static const std::regex pattern(R"((.+)\.([0-9]+)\.[0-9]+\.(tmp|old))");
  std::smatch m;
  const std::string name = p.filename().string();
  if (!std::regex_match(name, m, pattern)) return std::nullopt;
  return std::make_pair(std::stol(m[2].str()), p.parent_path() / m[1].str());
}

}  // namespace

int removeStaleTemporaries(const fs::path& dir) {
  int removed = 0;
  std::error_code ec;
  // Staging directories of `dir` beside it: .<name>.ibl-staging-<pid>.
  const fs::path parent = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
  std::string name = dir.filename().string();
  if (name.empty()) name = dir.parent_path().filename().string();
  const std::string prefix = "." + name + ".ibl-staging-";
  for (auto it = fs::directory_iterator(parent, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    if (entry.rfind(prefix, 0) != 0) continue;
    const std::string pid = entry.substr(prefix.size());
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) continue;
    if (processAlive(std::stol(pid))) continue;
    std::error_code removeError;
    fs::remove_all(it->path(), removeError);
    if (!removeError) ++removed;
  }
  // Temporary files in the directory and its subdirectories (an engine target's folder).
  if (!fs::is_directory(dir, ec)) return removed;
  std::vector<fs::path> stale;
  for (auto it = fs::recursive_directory_iterator(dir, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (it.depth() > 4) it.disable_recursion_pending();
    const auto owner = temporaryOwner(it->path());
    if (owner && !processAlive(owner->first) && it->is_regular_file(ec))
      stale.push_back(it->path());
  }
  for (const fs::path& p : stale) {
    std::error_code removeError;
    const fs::path destination = temporaryOwner(p)->second;
    if (p.extension() == ".old" && !fs::exists(destination, removeError))
      fs::rename(p, destination, removeError);  // a rename phase cut short: restore
    else
      fs::remove(p, removeError);
    if (!removeError) ++removed;
  }
  return removed;
}

}  // namespace ibl
