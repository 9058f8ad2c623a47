#pragma once
// Whole-file reads with a size limit, and atomic writes (temporary file, then rename).
#include <cstdint>
#include <filesystem>
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

}  // namespace ibl
