#pragma once
// API: stable
// Errors and resource limits shared by every part of ibl.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ibl {

// Every failure the library reports: one line, "<file>: <problem>".
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A request the tool cannot act on, found before any work: a bad option value, options that
// contradict each other, an output that would overwrite an input. The command exits with
// status 2 (1 for every other Error: a failure of the work itself).
class UsageError : public Error {
 public:
  using Error::Error;
};

// Throws Error("<what>: <problem>"). what: the file (path) or object at fault; problem: what is
// wrong, lower case, no final period.
[[noreturn]] void fail(std::string_view what, std::string_view problem);

// Throws UsageError("<option>: <problem>"). option: the option or value at fault ("--size",
// an output path).
[[noreturn]] void failUsage(std::string_view option, std::string_view problem);

// Limits applied to every input before memory is allocated for it (see README, "Limits").
inline constexpr int kMaxImageDimension = 65536;              // width or height of one image
inline constexpr std::uint64_t kMaxImagePixels = 1ull << 28;  // 268 M pixels, 3 GiB as float RGB
inline constexpr std::uint64_t kMaxFileBytes = 4ull << 30;    // 4 GiB

// Throws Error("<what>: empty image (WxH)") or ("<what>: image of WxH exceeds the limit ...")
// unless width x height (pixels) is a non-empty image within the limits above. what: the file.
void checkImageSize(std::string_view what, std::uint64_t width, std::uint64_t height);

}  // namespace ibl
