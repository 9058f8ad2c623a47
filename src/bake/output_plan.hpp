#pragma once
// The files of a bake before they are written (internal to src/bake/): bake.cpp plans its own
// outputs and targets.cpp those of the engine targets into one plan, which is encoded in
// parallel and written all or none.
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "ibl/bake/bake.hpp"

namespace ibl {

using Json = nlohmann::ordered_json;

// The files of a bake before they are written: each with a function that encodes it (run for
// all files in parallel, before the first byte is written) and the manifest's `outputs`.
struct PendingFile {
  std::filesystem::path path;  // relative to the output directory
  std::function<std::vector<std::uint8_t>()> encode;
  std::vector<std::uint8_t> bytes;
};
struct OutputPlan {
  std::vector<PendingFile> files;
  Json outputs = Json::array();

  void add(const std::string& path, std::function<std::vector<std::uint8_t>()> encode) {
    files.push_back({path, std::move(encode), {}});
  }
  void addText(const std::string& path, const std::string& text) {
    add(path, [text] { return std::vector<std::uint8_t>(text.begin(), text.end()); });
  }
};

// Records in a manifest entry, and warns, what a format's range clamps of an output.
// `engineFormat`: the format is the engine's (R11F_G11F_B10F, RGBD), not --format's.
void noteRangeLoss(Json& entry, const BakeOutputOptions& out, const std::string& file,
                   const RangeLoss& loss, std::string_view format, bool engineFormat = false);

// Plans the files of the engine targets of `out.targets` other than EngineTarget::Ibl
// (targets.cpp). `outDirName`: the name of the output directory (Filament's file stem);
// `panoramaSource`: the input was a panorama (Filament's axes depend on it).
void addTargetOutputs(OutputPlan& plan, const BakeResult& r, const BakeOptions& o,
                      const BakeOutputOptions& out, const std::string& outDirName,
                      bool panoramaSource);

}  // namespace ibl
