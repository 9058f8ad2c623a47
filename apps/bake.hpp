#pragma once
// `ibl bake`'s options and the steps of one bake, for the command and the Python module
// (python/): both parse the same options and run the same code.
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "ibl/bake/bake.hpp"

namespace ibl::cli {

struct BakeCliOptions {
  std::vector<std::string> inputs;  // none: the bundled default
  std::string list;                 // --list FILE: more inputs
  std::string shard;                // --shard K/N: the batch's inputs i with i mod N == K
  std::string output;
  std::string inputLayout;
  std::string layer;
  int size = 256;
  std::optional<int> levels;  // default: down to 8x8
  std::string mapping = "linear";
  std::string method = "direct";
  int samples = 64;
  bool fresnelWeighted = false;
  bool sheen = false;
  std::string sheenVisibility;  // empty: charlie
  std::vector<std::string> targets = {"ibl"};
  int irradianceSize = 32;
  int dfgSize = 128;
  int dfgSamples = 512;
  std::string shWindow = "off";
  float rotate = 0.0f;
  float clamp = 0.0f;  // 0: no limit
  std::string format = "rgba16f";
  bool exr = false;
  bool hdr = false;
  std::string layout = "hcross";
  bool noPreview = false;
  int previewSize = 96;
  bool force = false;
  bool extractSun = false;
  EnvScaleOptions envScale;  // --env-intensity, --env-illuminance
  std::string device = "cpu";
  bool listDevices = false;
  std::set<std::string> given;  // the options on the command line (CLI11's count)
};

// Adds the subcommand "bake" to `app` with its options, stored into `o` (no callback).
CLI::App* addBakeOptions(CLI::App& app, BakeCliOptions& o);
// Fills o.given from the options `cmd` parsed.
void noteGivenOptions(const CLI::App* cmd, BakeCliOptions& o);

// The checks of a bake of one input before any work (the options, the input, the output
// directory unless `outDir` is empty, memory and disk).
void checkSingleBake(const BakeCliOptions& o, const std::string& input, const std::string& outDir,
                     const GlobalOptions& global);

// An input of the command line (a file, a sky description, "" for the bundled default), or
// `pixels` named `input` (an image in memory), read with --input-layout, --layer and
// --extract-sun.
SourceEnvironment loadBakeInput(const BakeCliOptions& o, const std::string& input,
                                gpu::Context* device, const GlobalOptions& global,
                                std::optional<Image> pixels = std::nullopt);

// One bake: the environment scaled and clamped as the options say, baked, and what
// writeBakeOutputs needs to write it.
struct BakeRun {
  SourceEnvironment source;
  BakeOptions options;
  BakeResult result;
  BakeOutputOptions output;
  BakeSource facts;
};
// `input`: the source's name on the command line ("" for the bundled default), for the manifest.
BakeRun bakeSource(const BakeCliOptions& o, SourceEnvironment source, const std::string& input,
                   const ProgressFn& progress, gpu::Context* device, const GlobalOptions& global);

}  // namespace ibl::cli
