#pragma once
// The subcommands of the `ibl` executable: each registers its options and a callback.
#include <memory>
#include <optional>
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
enum class ComputeDevice;  // ibl/gpu/compute.hpp
}  // namespace ibl::gpu

namespace ibl::cli {

struct GlobalOptions {
  bool quiet = false;
};

// The one warning about pixels replaced on loading (NaN, infinite, negative), unless quiet.
void warnAboutReplacedPixels(std::string_view name, const InvalidPixelCounts& replaced,
                             const GlobalOptions& global);

// Where damaged pixels are (pixel_damage.hpp), for messages: "36 pixels in 1 region (x 304-309,
// y 110-115)", the largest three regions placed ("face +X: x .." on a cube), "no pixel" if none.
std::string damageSummary(const PixelDamage& damage, bool cube);

// What loading did to an environment's pixels, one line each, unless quiet: the damaged pixels
// (a warning) or their repair and its change of the environment's power (a note), then the
// replaced ones (warnAboutReplacedPixels).
void reportLoadedPixels(std::string_view name, const LoadedEnvironment& loaded,
                        const GlobalOptions& global);

// Fails, naming the file, when an environment holds no light after loading (every pixel zero,
// NaN, infinite or negative): baking it would give black maps.
void requireLight(const Environment& env, std::string_view name);

// Checks of numeric option values as CLI11 parses them; a failure reads "--opt: must be ..., not
// X" and, like every usage error, exits with status 2. Ranges print as people write them.
// Rejects NaN and infinite values (CLI11 parses "nan" and "inf").
const CLI::Validator& finiteNumber();
// A finite number from `lo` to `hi` inclusive.
CLI::Validator numberIn(double lo, double hi);
// A finite number above 0, or at least 0.
CLI::Validator positiveNumber();
CLI::Validator nonNegativeNumber();
// A power of two from `lo` to `hi` (texture sizes that mips halve down to 1).
CLI::Validator powerOfTwo(int lo, int hi);
// `count` comma-separated finite numbers ("1,2.5,-3"); a usage error naming `option` otherwise
// ("'nan' is not finite", "'x' is not a number", "expected 3 comma-separated numbers").
std::vector<float> parseNumbers(const std::string& text, std::size_t count, const char* option);

// --shard K/N (`ibl probe --grid`, `ibl bake` batches): the K-th of N disjoint parts of a list,
// K from 0; an item of index i belongs to the shard i mod N. A usage error naming --shard unless
// 0 <= K < N. The same rule in every command, so one scheduler's array (Slurm's
// $SLURM_ARRAY_TASK_ID, Kubernetes's $JOB_COMPLETION_INDEX) shards them all alike.
struct Shard {
  int k = 0;
  int n = 1;
  bool owns(std::size_t index) const { return static_cast<int>(index % n) == k; }
};
Shard parseShard(const std::string& text);

// A number for messages: 4096, 0.25, 1e+20 (no 309-digit doubles, no trailing zeros).
std::string formatNumber(double value);

// --device cpu, gpu or auto (which the option checks) as the library's choice, for
// gpu::openComputeDevice; a usage error for any other text.
gpu::ComputeDevice deviceChoice(const std::string& text);

// --env-intensity K and --env-illuminance LUX: scaling an environment into physical units
// (docs/cli.md#environments-in-physical-units). At most one of them.
struct EnvScaleOptions {
  std::optional<double> intensity;    // a factor, > 0
  std::optional<double> illuminance;  // lux on an upward plane, the sun included, > 0
  bool given() const { return intensity.has_value() || illuminance.has_value(); }
};
// Registers both options on `cmd`.
void addEnvScaleOptions(CLI::App* cmd, EnvScaleOptions& o);
// Usage errors: both options given; either with nothing to scale (`what`: "--env none").
void checkEnvScaleOptions(const EnvScaleOptions& o, const std::string& nothingToScale = {});

// What a scale did: the factor and, for the manifests, the option, the illuminance (lux) before
// and after, and the target of --env-illuminance.
struct EnvScale {
  double factor = 1.0;
  std::string option;              // "--env-intensity" or "--env-illuminance"; "" when not scaled
  double measuredLux = 0.0;        // before scaling, the sun included
  double targetLux = 0.0;          // --env-illuminance
  std::string recordJson() const;  // {"option": ..., "factor": ..., ...}; "" when not scaled
};
// The factor of the options for an environment of horizontal illuminance `measuredLux`
// (`name` for errors: "<name>: --env-illuminance: ..." when it is dark above the horizon).
EnvScale envScaleFor(const EnvScaleOptions& o, double measuredLux, std::string_view name);

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
// An environment given as an image in memory (the Python module's arrays), laid out by its
// shape or options.layout, its invalid pixels replaced as a file's are; format "array".
SourceEnvironment sourceFromImage(Image image, const std::string& name, const LoadOptions& options,
                                  bool extractSun, const GlobalOptions& global);
// --extract-sun: takes the sun out of the source (a panorama afterwards) into its lights.
void extractSourceSun(SourceEnvironment& source, const GlobalOptions& global);
// Scales a source environment and the suns it brings by --env-intensity / --env-illuminance
// (nothing without them), before anything else is done with it; the manifest records (lights
// and "environment_scale") follow. Prints a note with the factor unless quiet.
EnvScale scaleSourceEnvironment(SourceEnvironment& source, const EnvScaleOptions& o,
                                const GlobalOptions& global);

void addConvertCommand(CLI::App& app, const GlobalOptions& global);
void addInfoCommand(CLI::App& app, const GlobalOptions& global);
void addBakeCommand(CLI::App& app, const GlobalOptions& global);
void addRenderCommand(CLI::App& app, const GlobalOptions& global);
void addCompareCommand(CLI::App& app, const GlobalOptions& global);
void addViewCommand(CLI::App& app, const GlobalOptions& global);
void addProbeCommand(CLI::App& app, const GlobalOptions& global);
void addSkyCommand(CLI::App& app, const GlobalOptions& global);

}  // namespace ibl::cli
