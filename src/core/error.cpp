#include "ibl/core/error.hpp"

#include <fmt/format.h>

namespace ibl {

void fail(std::string_view what, std::string_view problem) {
  throw Error(fmt::format("{}: {}", what, problem));
}

void failUsage(std::string_view option, std::string_view problem) {
  throw UsageError(fmt::format("{}: {}", option, problem));
}

void checkImageSize(std::string_view what, std::uint64_t width, std::uint64_t height) {
  if (width == 0 || height == 0) fail(what, fmt::format("empty image ({}x{})", width, height));
  if (width > kMaxImageDimension || height > kMaxImageDimension || width * height > kMaxImagePixels)
    fail(what, fmt::format("image of {}x{} exceeds the limit ({} per side, {} pixels)", width,
                           height, kMaxImageDimension, kMaxImagePixels));
}

}  // namespace ibl
