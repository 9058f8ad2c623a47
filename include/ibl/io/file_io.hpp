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

}  // namespace ibl
