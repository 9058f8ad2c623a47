#pragma once
// `ibl compare`'s options and measurement, for the command and the Python module (python/):
// both parse the same options and run the same code.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "ibl/core/stats.hpp"

namespace ibl::cli {

struct CompareOptions {
  std::string a, b, mask, errorPng;
  double maxRelError = -1.0;
  double errorScale = 0.1;
  bool json = false;
};

// Adds the subcommand "compare" to `app` with its options, stored into `o` (no callback).
CLI::App* addCompareOptions(CLI::App& app, CompareOptions& o);

// A flat image file as `ibl compare` reads it (a cube map is an error naming the file).
Image readFlatImage(const std::string& path);
// Reads o.a, o.b (and o.mask) and measures, writing --error-png if asked.
ImageComparison compareFiles(const CompareOptions& o);
// The measurement of images already read (`nameA`, `nameB`, `maskName` for errors; `mask` the
// mask image's red channel, empty: none); writes --error-png if asked.
ImageComparison compareLoaded(const CompareOptions& o, const Image& a, const Image& b,
                              const std::vector<float>& mask, const std::string& nameA,
                              const std::string& nameB, const std::string& maskName);
// What --json prints.
nlohmann::ordered_json comparisonJson(const ImageComparison& c);

}  // namespace ibl::cli
