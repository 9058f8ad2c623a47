#pragma once
// API: internal (may change without notice; file helpers of the library and the front end)
// Whole-file reads with a size limit, and atomic writes (temporary file, then rename).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <vector>

namespace ibl {

// Reads a whole file; throws Error("<path>: ...") if it is missing, unreadable or larger
// than kMaxFileBytes.
std::vector<std::uint8_t> readFileBytes(const std::filesystem::path& path);

// Writes `bytes` to a temporary file beside `path`, then renames it into place, so that a
// reader never sees a half-written file. Creates missing parent directories.
void writeFileAtomic(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

// A file's destination and its whole content.
struct EncodedFile {
  std::filesystem::path path;
  std::vector<std::uint8_t> bytes;
};

// Writes several files all or none. Every file is first written to a temporary file beside its
// destination; only when all of them are complete are they renamed into place, each existing
// file kept aside until every rename has succeeded. Any failure (a full disk, a destination
// that is a directory, a rename refused) removes what was written, restores what was replaced,
// and throws Error naming the file concerned.
void writeFilesTogether(std::span<const EncodedFile> files);

// The bytes free for this user on the file system that holds `where` (a file or directory that
// may not exist yet: its nearest existing ancestor is asked); none when it cannot be told.
std::optional<std::uint64_t> freeDiskBytes(const std::filesystem::path& where);

// --- Temporaries ---
// Every temporary the writes above make is named PATH.<pid>.<n>.tmp beside its destination
// (PATH.<pid>.<n>.old for a file kept aside while its replacement moves in), and a new output
// directory is staged as .<name>.ibl-staging-<pid> beside it. Each is registered while it
// exists, so that an interrupted process can remove its own, and a later process can tell
// which ones no live process owns.

// A directory this process stages, created empty (and its parents) and registered, so that
// removeTemporariesOfThisProcess removes it whole, for as long as the object lives.
class StagingDirectory {
 public:
  explicit StagingDirectory(std::filesystem::path dir);
  ~StagingDirectory();
  StagingDirectory(const StagingDirectory&) = delete;
  StagingDirectory& operator=(const StagingDirectory&) = delete;
  const std::filesystem::path& path() const { return dir_; }
  // Renames the finished directory to `destination` (which must not exist), in one step with
  // its leaving the registry: an interrupt finds it either staged (and removes it) or in place.
  void moveTo(const std::filesystem::path& destination);

 private:
  std::filesystem::path dir_;
};

// The staging directory of a new output directory `outDir` for process `pid`.
std::filesystem::path stagingDirectoryFor(const std::filesystem::path& outDir, long pid);

// Removes every registered temporary of this process and restores the files kept aside; waits
// for a rename phase in progress to end first, so that no destination is left missing. For an
// interrupt handler (not a signal handler: it locks and allocates), just before the process
// exits. It keeps the registry locked, so that no temporary is created after it.
void removeTemporariesOfThisProcess();

// Removes the temporaries in `dir` (and the staging directories of `dir` beside it) whose
// process no longer runs, restoring a file kept aside whose destination is missing. Returns how
// many it removed or restored. Temporaries of live processes are left alone.
int removeStaleTemporaries(const std::filesystem::path& dir);

}  // namespace ibl
