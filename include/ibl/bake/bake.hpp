#pragma once
// API: stable
// The bake: an HDR environment in, the assets of image-based lighting out (source cube with
// mips, GGX-prefiltered specular cube, irradiance cube, SH9, DFG table), each written as KTX2
// (and optionally EXR / HDR), a preview, and a manifest stating every convention.
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ibl/bake/prefilter.hpp"
#include "ibl/bake/targets.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/export.hpp"
#include "ibl/io/pixel_formats.hpp"
#include "ibl/math/brdf.hpp"
#include "ibl/math/sh.hpp"

namespace ibl {

struct BakeOptions {
  PrefilterOptions specular;          // size (also the source cube's), levels, mapping, method
  bool fresnelWeighted = false;       // also bake the C(n, l)-weighted pair (F0 = 0 and F0 = 1)
  int irradianceSize = 32;            // texels per side of the irradiance cube
  int dfgSize = 128;                  // texels per side of the DFG (and sheen) table
  int dfgSamples = 512;               // samples per texel of those tables
  ShWindow shWindow = ShWindow::Off;  // the SH9 coefficients' window against ringing
  float rotateDegrees = 0.0f;         // about +Y, degrees (rotationY in env/resample.hpp: +X to -Z)
  // Also prefilter the environment with the Charlie sheen lobe (the same levels and roughness
  // mapping as the specular chain) and integrate the sheen table (manifest roles sheen and
  // sheen_dfg). The glTF Sample Viewer target always does.
  bool sheen = false;
  // The sheen lobe's visibility in the sheen table (recorded in manifest.json; renders of the
  // bake use the same).
  SheenVisibility sheenVisibility = SheenVisibility::Charlie;
  // What to write (writeBakeOutputs) and so what to compute: the ibl set, engine targets.
  std::vector<EngineTarget> targets = {EngineTarget::Ibl};
  bool wants(EngineTarget t) const;  // t is among `targets`
  // Whether the sheen chain and table are baked (asked for, or needed by a target).
  bool wantsSheen() const { return sheen || wants(EngineTarget::GltfSampleViewer); }
};

struct BakeResult {
  CubeMap source;    // area-resampled source with its full mip chain
  CubeMap specular;  // level m: roughness roughnessForLevel(m), options.specular.mapping
  std::vector<LevelMethod> specularLevels;               // how each specular level was computed
  std::optional<CubeMap> specularF0Zero, specularF0One;  // with fresnelWeighted
  CubeMap irradiance;             // E / pi, one level of irradianceSize (the radiance's units)
  Sh9 sh;                         // radiance coefficients (windowed if asked)
  Image dfg;                      // RGB = A, B, diffuse; dfgSize^2 (dfg.hpp)
  std::optional<CubeMap> sheen;   // Charlie-prefiltered, with wantsSheen()
  std::optional<Image> sheenDfg;  // R = E of the sheen lobe (integrateSheenDfgLut)
  std::optional<CubeMap> filamentSpecular;  // cmgen's chain (levels, mapping), our axes
  std::optional<CubeMap> babylonSpecular;   // Babylon's chain (to 1^2, its mapping), our axes
  std::map<std::string, double> timingsMs;  // per stage, milliseconds of wall time
  std::string device = "cpu";               // "cpu", or the Vulkan device's name
  // The SH window's factor per band, as applied to sh (1, 1, 1 without a window).
  std::array<float, 3> shWindowFactors = {1.0f, 1.0f, 1.0f};
};

namespace gpu {
class Context;
}

// Fails with a UsageError when options contradict each other (the glTF Sample Viewer reads a
// linear roughness mapping). bakeEnvironment checks them too; a front end calls it before
// reading any input. Throws UsageError("--target gltf-sample-viewer: ...").
void checkBakeOptions(const BakeOptions& options);

// Runs every stage on all cores. The result does not depend on the number of threads. With a
// GPU context, every stage runs as compute shaders (the ring prefilter combines its passes on
// the host). env: any layout, in its own linear radiance units (the outputs keep them);
// progress: one stage per output (ProgressFn). Throws UsageError as checkBakeOptions, Error
// ("prefilter: ...") unless options.specular.size is a power of two.
BakeResult bakeEnvironment(const Environment& env, const BakeOptions& options,
                           const ProgressFn& progress = {}, gpu::Context* device = nullptr);

struct BakeOutputOptions {
  PixelFormat format = PixelFormat::Rgba16f;  // KTX2 cube maps (the DFG table is always RGBA16F)
  bool exr = false;                           // also EXR files (half float)
  bool hdr = false;                           // also Radiance HDR files
  Layout layout = Layout::HCross;  // of the EXR / HDR copies: a cross, strip, faces or equirect
  bool preview = true;   // preview.png (material grid) and PNG views (with the ibl target)
  int previewCell = 96;  // pixels per sphere of preview.png (6 x 2 spheres)
  bool force = false;    // write into a non-empty directory (replacing an earlier bake's files)
  // Called with one line for each output whose values exceed its format's range (they are
  // clamped to it: no output holds an infinity); the manifest records it too.
  std::function<void(const std::string&)> warn;
  // Hears of the files encoded, as stage "writing N files" (the encoding is the long part).
  ProgressFn progress;
  // More cube maps to write as KTX2 (role = file stem), e.g. a probe's visibility.
  std::vector<std::pair<std::string, const CubeMap*>> extraCubes;
  // A JSON object whose members join the manifest's top level (a probe's "probe" record).
  std::string manifestRecords;
};

// Facts about the input, recorded in the manifest.
struct BakeSource {
  std::string path;  // "" for the bundled default
  std::string format;
  std::string layout;           // "equirect" for a panorama (and a sky), else a cube layout
  int width = 0, height = 0;    // of the input image, pixels
  InvalidPixelCounts replaced;  // NaN, infinite and negative components set to 0 on loading
  float clamp = 0.0f;   // the radiance limit applied before baking (--clamp, input units), 0: none
  RangeLoss clampLoss;  // what it removed
};

// Encodes everything, then writes it into `outDir`, all files or none. The ibl target writes
// into `outDir` itself, another target too when it is the only one, else into
// `outDir`/<target name>/; manifest.json lists every file with its target. a missing directory is
// staged and renamed into place; an existing one must be empty unless output.force, and then
// the earlier bake's files (as its manifest lists them) are replaced or removed, other files
// kept. Returns the written paths. Throws Error naming the directory or file (not writable, not
// enough disk space, an encoding failure); nothing is left half-written.
std::vector<std::filesystem::path> writeBakeOutputs(const BakeResult& result,
                                                    const BakeOptions& options,
                                                    const BakeOutputOptions& output,
                                                    const BakeSource& source,
                                                    const std::filesystem::path& outDir);

// The text of the manifest.json writeBakeOutputs writes into `outDir` (nothing encoded or
// written; only the directory's name is used, by engine targets that name files after it).
std::string bakeManifestJson(const BakeResult& result, const BakeOptions& options,
                             const BakeOutputOptions& output, const BakeSource& source,
                             const std::filesystem::path& outDir);
// Fails, naming the directory, unless writeBakeOutputs can write `outDir`: a directory that
// does not exist yet (its nearest existing parent must be writable), or an existing writable
// directory that is empty or, with `force`, holds anything (an earlier bake's files are
// replaced). writeBakeOutputs checks it again; a front end calls it before any work.
void checkBakeOutputDirectory(const std::filesystem::path& outDir, bool force);

// The peak memory of bakeEnvironment followed by writeBakeOutputs (on the CPU), and the bytes
// the outputs take on disk, estimated from the options alone (the input's own size aside), from
// a model fitted to measured bakes (docs/bake.md, "Memory and disk"): an upper bound within
// about 20 %.
std::uint64_t estimateBakeMemoryBytes(const BakeOptions& options, const BakeOutputOptions& output);
std::uint64_t estimateBakeOutputBytes(const BakeOptions& options, const BakeOutputOptions& output);

// Multiplies the radiance a bake holds by `factor` (> 0 and finite), as if the environment had
// been scaled before baking: every stage is linear in the radiance, so the source, specular
// (and its Fresnel-weighted pair, Filament's and Babylon's chains), sheen and irradiance cubes
// and the SH9 coefficients are scaled; the DFG and sheen tables, which hold no radiance, are
// not. Throws Error("<name>: ...") if a value would leave the range of a float.
void scaleBake(BakeResult& bake, double factor, std::string_view name = "bake");

// Reads a bake written by writeBakeOutputs back (specular, irradiance, source, DFG, SH9, the
// sheen pair, and the roughness mapping and sheen visibility from its manifest), for rendering
// without baking again. options, if given, receives the specular size, mapping and sheen
// visibility. Throws Error naming the directory, manifest.json or the file at fault.
BakeResult loadBake(const std::filesystem::path& dir, BakeOptions* options);
// A cube map file of a bake (KTX2, every level), e.g. a probe's coverage; throws, naming the
// file, when it is not a cube map.
CubeMap readBakedCube(const std::filesystem::path& path);

}  // namespace ibl
