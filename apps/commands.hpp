#pragma once
// The subcommands of the `ibl` executable: each registers its options and a callback.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "ibl/core/image.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/render/light.hpp"

namespace ibl::gpu {
class Context;
}

namespace ibl::cli {

struct GlobalOptions {
  bool quiet = false;
};

// The one warning about pixels replaced on loading (NaN, infinite, negative), unless quiet.
void warnAboutReplacedPixels(std::string_view name, const InvalidPixelCounts& replaced,
                             const GlobalOptions& global);

// Fails, naming the file, when an environment holds no light after loading (every pixel zero,
// NaN, infinite or negative): baking it would give black maps.
void requireLight(const Environment& env, std::string_view name);

// Rejects NaN and infinite values of a numeric option (CLI11 parses "nan" and "inf").
const CLI::Validator& finiteNumber();

// The Vulkan context for --device gpu (required: throws when there is none), none for cpu, and
// for auto a real GPU if there is one (the software device is slower than the CPU paths, so
// auto does not pick it).
std::unique_ptr<gpu::Context> openDevice(const std::string& choice);

// The sky's panorama of `p` on `device`, or on the CPU without one (gpu::skyPanorama,
// SkyModel::panorama).
Image skyImage(const SkyParameters& p, int width, int height, bool paintSun, gpu::Context* device);

// An environment named on the command line (a file, a sky description "sky:...", or the
// bundled default when `input` is empty) with the lights it brings: the sky's sun, or the sun
// --extract-sun took out of an HDRI. A sky is computed on `device` when one is given.
struct SourceEnvironment {
  LoadedEnvironment loaded;
  std::string name;             // for messages
  std::vector<Light> lights;    // the sun, if any
  std::string manifestRecords;  // JSON object: {"lights": [...], "sky": {...}} (may be empty)
};
SourceEnvironment loadSourceEnvironment(const std::string& input, const LoadOptions& options,
                                        bool extractSun, const GlobalOptions& global,
                                        gpu::Context* device = nullptr);

void addConvertCommand(CLI::App& app, const GlobalOptions& global);
void addInfoCommand(CLI::App& app, const GlobalOptions& global);
void addBakeCommand(CLI::App& app, const GlobalOptions& global);
void addRenderCommand(CLI::App& app, const GlobalOptions& global);
void addCompareCommand(CLI::App& app, const GlobalOptions& global);
void addViewCommand(CLI::App& app, const GlobalOptions& global);
void addProbeCommand(CLI::App& app, const GlobalOptions& global);
void addSkyCommand(CLI::App& app, const GlobalOptions& global);

}  // namespace ibl::cli
