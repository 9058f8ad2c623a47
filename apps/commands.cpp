#include "commands.hpp"

#include <cstdio>

#include <fmt/core.h>

#include "ibl/core/error.hpp"
#include "ibl/core/stats.hpp"

namespace ibl::cli {

void warnAboutReplacedPixels(std::string_view name, const InvalidPixelCounts& replaced,
                             const GlobalOptions& global) {
  if (replaced.total() == 0 || global.quiet) return;
  fmt::print(stderr,
             "ibl: warning: {}: replaced {} NaN, {} infinite and {} negative pixel components by "
             "0\n",
             name, replaced.nan, replaced.infinite, replaced.negative);
}

void requireLight(const Environment& env, std::string_view name) {
  if (!brightestDirection(env))
    fail(std::string(name),
         "holds no light: every pixel is zero, NaN, infinite or negative after loading");
}

}  // namespace ibl::cli
