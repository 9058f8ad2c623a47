#include "commands.hpp"

#include <cmath>
#include <cstdio>

#include <fmt/core.h>

#include "ibl/core/error.hpp"
#include "ibl/core/stats.hpp"

namespace ibl::cli {

void warnAboutReplacedPixels(std::string_view name, const InvalidPixelCounts& replaced,
                             const GlobalOptions& global) {
  if (replaced.total() == 0 || global.quiet) return;
  // Small negative values are common (lossy EXR compression, denoisers, color-space
  // conversions) and harmless once read as 0: a note. NaN and infinities are damage: a warning.
  if (replaced.nan == 0 && replaced.infinite == 0) {
    fmt::print(stderr, "ibl: note: {}: {} negative pixel components read as 0\n", name,
               replaced.negative);
    return;
  }
  fmt::print(stderr,
             "ibl: warning: {}: replaced {} NaN, {} infinite and {} negative pixel components by "
             "0\n",
             name, replaced.nan, replaced.infinite, replaced.negative);
}

const CLI::Validator& finiteNumber() {
  static const CLI::Validator validator(
      [](const std::string& text) -> std::string {
        double value = 0.0;
        try {
          value = std::stod(text);
        } catch (const std::exception&) {
          return {};  // not a number at all: the option's own conversion reports it
        }
        return std::isfinite(value) ? std::string() : "'" + text + "' is not a finite number";
      },
      "FINITE");
  return validator;
}

void requireLight(const Environment& env, std::string_view name) {
  if (!brightestDirection(env))
    fail(std::string(name),
         "holds no light: every pixel is zero, NaN, infinite or negative after loading");
}

}  // namespace ibl::cli
