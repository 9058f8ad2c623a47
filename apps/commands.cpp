#include "commands.hpp"

#include <cstdio>

#include <fmt/core.h>

namespace ibl::cli {

void warnAboutReplacedPixels(std::string_view name, const InvalidPixelCounts& replaced,
                             const GlobalOptions& global) {
  if (replaced.total() == 0 || global.quiet) return;
  fmt::print(stderr,
             "ibl: warning: {}: replaced {} NaN, {} infinite and {} negative pixel components by "
             "0\n",
             name, replaced.nan, replaced.infinite, replaced.negative);
}

}  // namespace ibl::cli
