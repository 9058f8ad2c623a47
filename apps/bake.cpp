// `ibl bake`: an HDR environment in, engine-ready IBL assets out.
#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include "bake.hpp"
#include "batch.hpp"
#include "commands.hpp"
#include "ibl/bake/bake.hpp"
#include "ibl/core/error.hpp"
#include "ibl/env/default_environment.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/gpu/compute.hpp"
#include "preflight.hpp"
#include "progress.hpp"

namespace ibl::cli {

namespace {

// The library's options from the command line's (nothing read yet).
BakeOptions bakeOptionsOf(const BakeCliOptions& o) {
  BakeOptions options;
  options.specular.size = o.size;
  options.specular.levels = o.levels.value_or(0);
  options.specular.mapping =
      o.mapping == "frostbite" ? RoughnessMapping::Frostbite : RoughnessMapping::Linear;
  options.specular.method =
      o.method == "sampled" ? PrefilterMethod::Sampled : PrefilterMethod::Direct;
  options.specular.samples = o.samples;
  options.fresnelWeighted = o.fresnelWeighted;
  options.sheen = o.sheen;
  if (!o.sheenVisibility.empty())
    options.sheenVisibility = *parseSheenVisibility(o.sheenVisibility);
  options.targets.clear();
  for (const std::string& t : o.targets) {
    const EngineTarget target = *parseEngineTarget(t);
    if (!options.wants(target)) options.targets.push_back(target);
  }
  options.irradianceSize = o.irradianceSize;
  options.dfgSize = o.dfgSize;
  options.dfgSamples = o.dfgSamples;
  options.shWindow = o.shWindow == "lanczos" ? ShWindow::Lanczos
                     : o.shWindow == "cmgen" ? ShWindow::Cmgen
                                             : ShWindow::Off;
  options.rotateDegrees = o.rotate;
  return options;
}

BakeOutputOptions outputOptionsOf(const BakeCliOptions& o) {
  BakeOutputOptions output;
  output.format = *parsePixelFormat(o.format);
  output.exr = o.exr;
  output.hdr = o.hdr;
  output.layout = *parseLayout(o.layout);
  output.preview = !o.noPreview;
  output.previewCell = o.previewSize;
  output.force = o.force;
  return output;
}

// Each option the user gave that some requested target writes in its own fixed way: refused
// when no requested target takes it, else a note naming the targets that do not.
void checkTargetsTakeTheOptions(const BakeCliOptions& o, const BakeOptions& options,
                                const BakeOutputOptions& output, const GlobalOptions& global) {
  using S = BakeSetting;
  const std::pair<const char*, S> settings[] = {
      {"--format", S::Format},       {"--levels", S::Levels},
      {"--mapping", S::Mapping},     {"--irradiance-size", S::IrradianceSize},
      {"--dfg-size", S::DfgTable},   {"--dfg-samples", S::DfgTable},
      {"--exr", S::FileCopies},      {"--hdr", S::FileCopies},
      {"--layout", S::FileCopies},   {"--preview-size", S::Previews},
      {"--no-preview", S::Previews}, {"--fresnel-weighted", S::FresnelWeighted},
      {"--sheen", S::Sheen},         {"--sh-window", S::ShWindow}};
  for (const auto& [option, setting] : settings) {
    if (!o.given.count(option)) continue;
    std::vector<std::string> taking, fixed;
    for (EngineTarget t : options.targets) {
      const auto instead = fixedByTarget(t, setting, output.format);
      if (instead)
        fixed.push_back(fmt::format("--target {} writes {}", targetName(t), *instead));
      else
        taking.emplace_back(targetName(t));
    }
    if (fixed.empty()) continue;
    std::string reasons;
    for (const auto& f : fixed) reasons += (reasons.empty() ? "" : "; ") + f;
    if (taking.empty()) failUsage(option, fmt::format("no target takes it: {}", reasons));
    if (!global.quiet)
      fmt::print(stderr, "ibl: note: {} applies to the {} target(s) only: {}\n", option,
                 fmt::join(taking, ", "), reasons);
  }
}

// Bakes one input ("" for the bundled default) into `outDir`; returns the summary line.
std::string bakeOne(const BakeCliOptions& o, const std::string& input, const std::string& outDir,
                    bool showProgress, gpu::Context* device, const GlobalOptions& global) {
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  SourceEnvironment source = loadBakeInput(o, input, device, global);
  ProgressLine line(showProgress);
  const BakeRun run = bakeSource(o, std::move(source), input, line.callback(), device, global);
  const auto files = writeBakeOutputs(run.result, run.options, run.output, run.facts, outDir);
  return fmt::format("baked {} into {}: {} files in {:.2f} s (bake {:.0f} ms)", run.source.name,
                     outDir, files.size(), elapsed(), run.result.timingsMs.at("total"));
}

// Everything that can be known wrong before the work: the options, the inputs (there and
// readable), each output directory (writable, empty or --force, holding no input), and the
// memory and disk space the bakes need.
void checkBeforeBaking(const BakeCliOptions& o, const std::vector<std::string>& inputs,
                       const std::vector<std::string>& outDirs, const GlobalOptions& global) {
  const BakeOptions options = bakeOptionsOf(o);
  const BakeOutputOptions output = outputOptionsOf(o);
  checkBakeOptions(options);
  checkEnvScaleOptions(o.envScale);
  checkTargetsTakeTheOptions(o, options, output, global);
  for (const std::string& input : inputs) {
    if (!isSkySpec(input)) continue;
    if (o.extractSun)
      failUsage("--extract-sun",
                fmt::format("contradicts {}: a sky's sun is a light already", input));
    for (const char* option : {"--input-layout", "--layer"})
      if (o.given.count(option))
        failUsage(option, fmt::format("reads a file; {} is computed", input));
  }
  std::vector<std::filesystem::path> inputFiles;
  for (const std::string& input : inputs) {
    requireReadable(input);
    for (auto& f : filesOfInput(input)) inputFiles.push_back(std::move(f));
  }
  if (!o.list.empty()) inputFiles.emplace_back(o.list);
  std::uint64_t diskBytes = 0;
  for (const std::string& dir : outDirs) {  // none: a bake kept in memory (Python)
    refuseInputsInside(dir, inputFiles);
    checkBakeOutputDirectory(dir, o.force);
    diskBytes += estimateBakeOutputBytes(options, output);
  }
  // Several inputs bake at once (the task scheduler shares the cores): at most two at their
  // peak together is what the measured batches show; one at a time on a GPU.
  const std::uint64_t memory =
      estimateBakeMemoryBytes(options, output) * std::clamp<std::size_t>(outDirs.size(), 1, 2);
  requireMemory(memory, fmt::format("--size {}", o.size),
                "bake with a smaller --size, or fewer targets");
  if (!outDirs.empty()) requireDiskSpace(outDirs.front(), diskBytes, "the bake");
}

// The usage errors of options that contradict each other, the output directory aside.
void checkOptionPairs(const BakeCliOptions& o) {
  const int mipCount = std::bit_width(static_cast<unsigned>(o.size));
  if (o.levels && *o.levels > mipCount)
    failUsage("--levels", fmt::format("{} levels need a cube of at least {}^2; --size {} has {} "
                                      "(down to 1x1)",
                                      *o.levels, 1 << (*o.levels - 1), o.size, mipCount));
  if (!o.sheenVisibility.empty() && !o.sheen &&
      std::find(o.targets.begin(), o.targets.end(), "gltf-sample-viewer") == o.targets.end())
    failUsage("--sheen-visibility",
              "chooses the visibility of the sheen table, which only --sheen or --target "
              "gltf-sample-viewer bakes");
  if (o.noPreview && o.given.count("--preview-size"))
    failUsage("--preview-size", "contradicts --no-preview: there is no preview to size");
  if (o.given.count("--layout") && !o.exr && !o.hdr)
    failUsage("--layout",
              "lays out the EXR and HDR copies: add --exr or --hdr (the KTX2 files "
              "are cube maps)");
  if (o.given.count("--samples") && o.method != "sampled")
    failUsage("--samples",
              "counts the GGX samples of --method sampled; --method direct (the "
              "default) integrates in rings");
}

void runBake(const BakeCliOptions& o, const GlobalOptions& global) {
  if (o.listDevices) {
    const auto devices = gpu::listDevices();
    if (devices.empty()) fmt::print("no Vulkan device\n");
    for (const auto& d : devices)
      fmt::print("{} ({}, Vulkan {}.{})\n", d.name, d.type, d.apiVersion >> 22,
                 (d.apiVersion >> 12) & 0x3ff);
    return;
  }
  if (o.output.empty()) failUsage("--output", "an output directory is required");
  checkOptionPairs(o);
  const bool batch =
      o.inputs.size() > 1 || !o.list.empty() ||
      (o.inputs.size() == 1 && o.inputs[0].find_first_of("*?[") != std::string::npos &&
       !std::filesystem::exists(o.inputs[0]));
  std::optional<Shard> shard;
  if (!o.shard.empty()) {
    shard = parseShard(o.shard);
    if (!batch) failUsage("--shard", "splits a batch: it needs --list FILE or several inputs");
  }
  std::vector<std::string> inputs =
      batch ? expandInputs(o.inputs, o.list)
            : std::vector<std::string>{o.inputs.empty() ? std::string() : o.inputs[0]};
  if (shard) {
    // The whole batch is expanded and checked for colliding names first, so that every shard
    // agrees on the indices (the inputs on the command line, then the list's lines, in order).
    std::vector<std::string> mine;
    for (std::size_t i = 0; i < inputs.size(); ++i)
      if (shard->owns(i)) mine.push_back(inputs[i]);
    if (mine.empty()) {
      if (!global.quiet)
        fmt::print(stderr, "ibl: note: --shard {}: none of the batch's {} inputs is this shard's\n",
                   o.shard, inputs.size());
      return;
    }
    inputs = std::move(mine);
  }
  std::vector<std::string> outDirs;
  for (const std::string& input : inputs)
    outDirs.push_back(batch ? (std::filesystem::path(o.output) / batchName(input)).string()
                            : o.output);
  checkBeforeBaking(o, inputs, outDirs, global);
  const std::unique_ptr<gpu::Context> device = gpu::openComputeDevice(deviceChoice(o.device));
  if (!batch) {
    const std::string line = bakeOne(
        o, inputs[0], o.output, !global.quiet && ::isatty(STDERR_FILENO), device.get(), global);
    if (!global.quiet) fmt::print(stderr, "{}\n", line);
    return;
  }
  // A batch: each input into OUTDIR/<name>/, several at once (one at a time on a GPU).
  runBatch(
      inputs,
      [&](const std::string& input) {
        return bakeOne(o, input, (std::filesystem::path(o.output) / batchName(input)).string(),
                       false, device.get(), global);
      },
      device == nullptr, global);
}

}  // namespace

void checkSingleBake(const BakeCliOptions& o, const std::string& input, const std::string& outDir,
                     const GlobalOptions& global) {
  checkOptionPairs(o);
  checkBeforeBaking(o, {input},
                    outDir.empty() ? std::vector<std::string>{} : std::vector<std::string>{outDir},
                    global);
}

SourceEnvironment loadBakeInput(const BakeCliOptions& o, const std::string& input,
                                gpu::Context* device, const GlobalOptions& global,
                                std::optional<Image> pixels) {
  LoadOptions loadOptions;
  if (!o.inputLayout.empty()) loadOptions.layout = parseLayout(o.inputLayout);
  loadOptions.layer = o.layer;
  if (pixels) return sourceFromImage(std::move(*pixels), input, loadOptions, o.extractSun, global);
  return loadSourceEnvironment(input, loadOptions, o.extractSun, global, device);
}

BakeRun bakeSource(const BakeCliOptions& o, SourceEnvironment source, const std::string& input,
                   const ProgressFn& progress, gpu::Context* device, const GlobalOptions& global) {
  BakeRun run;
  run.source = std::move(source);
  const std::string& name = run.source.name;
  LoadedEnvironment& loaded = run.source.loaded;
  requireLight(loaded.environment, name);
  scaleSourceEnvironment(run.source, o.envScale, global);  // before anything else
  RangeLoss clampLoss;
  if (o.clamp > 0.0f) {
    clampLoss = clampEnvironment(loaded.environment, o.clamp);
    if (!global.quiet)
      fmt::print(stderr, "ibl: note: {}: --clamp: {}\n", name, describe(clampLoss, o.clamp));
  }

  run.options = bakeOptionsOf(o);
  if (device && progress) {  // a line naming the device, a stage without work of its own
    const std::string stage = fmt::format("GPU stages on {}", device->device().name);
    progress(stage, 0.0);
    progress(stage, 1.0);
  }
  run.result = bakeEnvironment(loaded.environment, run.options, progress, device);

  run.output = outputOptionsOf(o);
  run.output.manifestRecords = run.source.manifestRecords;
  run.output.warn = [&global](const std::string& message) {
    if (!global.quiet) fmt::print(stderr, "ibl: warning: {}\n", message);
  };
  const Environment& env = loaded.environment;
  run.facts = BakeSource{input,
                         loaded.format,
                         std::string(layoutName(env.layout)),
                         env.isCube() ? env.cube.size() : env.equirect.width,
                         env.isCube() ? env.cube.size() : env.equirect.height,
                         loaded.replaced,
                         o.clamp,
                         clampLoss};
  run.output.progress = progress;
  return run;
}

void noteGivenOptions(const CLI::App* cmd, BakeCliOptions& o) {
  for (const CLI::Option* option : cmd->get_options())
    if (option->count() > 0) o.given.insert(option->get_name());
}

void addBakeCommand(CLI::App& app, const GlobalOptions& global) {
  auto opts = std::make_shared<BakeCliOptions>();
  CLI::App* cmd = addBakeOptions(app, *opts);
  cmd->callback([opts, cmd, &global] {
    noteGivenOptions(cmd, *opts);
    runBake(*opts, global);
  });
}

CLI::App* addBakeOptions(CLI::App& app, BakeCliOptions& o) {
  BakeCliOptions* opts = &o;
  CLI::App* cmd = app.add_subcommand(
      "bake", "Bake an HDR environment into IBL assets (specular, irradiance, SH9, DFG)");
  cmd->add_option("inputs", opts->inputs,
                  "Environments (any `ibl convert` input; a quoted pattern such as 'hdri/*.exr' "
                  "is expanded; or a physical sky, sky:elevation=30,azimuth=120 (see ibl sky), "
                  "its sun listed in the manifest); default: the bundled sunset.exr. Several: "
                  "each is baked into OUTDIR/<name>/");
  cmd->add_option("--list", opts->list,
                  "Also bake the files this text file lists, one per line (a batch)");
  cmd->add_option("--shard", opts->shard,
                  "Bake the K-th of N disjoint parts of a batch (K/N, K from 0): the inputs whose "
                  "index in the batch (the command line's, then the list's) is K modulo N");
  cmd->add_option("-o,--output", opts->output,
                  "Output directory (required; created with its missing parents); of a batch: the "
                  "parent of one directory per input");
  cmd->add_option("--device", opts->device,
                  "cpu, gpu (every stage in Vulkan compute: resampling, mips, specular, "
                  "irradiance, SH9, DFG), or auto (a real GPU if present)")
      ->check(CLI::IsMember({"cpu", "gpu", "auto"}))
      ->capture_default_str();
  cmd->add_flag("--list-devices", opts->listDevices, "List the Vulkan devices and exit");
  cmd->add_option("--input-layout", opts->inputLayout,
                  "Input layout (default: from the image shape)")
      ->check(CLI::IsMember({"equirect", "cross", "hcross", "vcross", "hstrip", "vstrip", "faces",
                             "mirrorball", "angular"}));
  cmd->add_option("--layer", opts->layer,
                  "EXR layer to read (ViewLayer.Combined); default: the plain R, G, B channels or "
                  "the only color layer");
  cmd->add_option("--size", opts->size, "Specular (and source) cube size, a power of two")
      ->check(powerOfTwo(1, 4096))
      ->capture_default_str();
  cmd->add_option("--levels", opts->levels, "Specular mip levels (default: down to 8x8)")
      ->check(numberIn(1, 13));
  cmd->add_option("--mapping", opts->mapping,
                  "Roughness of level m: linear r = m/(L-1), frostbite r = (m/(L-1))^2")
      ->check(CLI::IsMember({"linear", "frostbite"}))
      ->capture_default_str();
  cmd->add_option("--method", opts->method,
                  "Specular convolution: direct (quadrature in rings) or sampled (FIS)")
      ->check(CLI::IsMember({"direct", "sampled"}))
      ->capture_default_str();
  cmd->add_option("--samples", opts->samples, "GGX samples per texel with --method sampled")
      ->check(numberIn(1, 65536))
      ->capture_default_str();
  cmd->add_flag("--fresnel-weighted", opts->fresnelWeighted,
                "Also bake the C(n,l)-weighted specular pair (specular_f0_0, specular_f0_1)");
  cmd->add_flag("--sheen", opts->sheen,
                "Also bake the sheen (Charlie) prefiltered cube and its table (sheen, sheen_dfg)");
  cmd->add_option("--sheen-visibility", opts->sheenVisibility,
                  "The sheen lobe's visibility in the sheen table: charlie (Estevez & Kulla, "
                  "KHR_materials_sheen's; default) or neubelt (simpler, gains energy at grazing "
                  "angles); recorded in manifest.json")
      ->check(CLI::IsMember({"charlie", "neubelt"}));
  cmd->add_option("--target", opts->targets,
                  "What to write, one or several (comma-separated): ibl (our KTX2 set), filament "
                  "(cmgen --deploy's KTX files and sh.txt), gltf-sample-viewer "
                  "(glTF-IBL-Sampler's ggx/, lambertian/, charlie/ and LUT PNGs), dds (DDS cube "
                  "maps with mips), babylon (a Babylon.js .env). Several: ibl in OUTDIR, the "
                  "others in OUTDIR/<target>/")
      ->delimiter(',')
      ->check(CLI::IsMember({"ibl", "filament", "gltf-sample-viewer", "dds", "babylon"}))
      ->capture_default_str();
  cmd->add_option("--irradiance-size", opts->irradianceSize, "Irradiance cube size")
      ->check(powerOfTwo(1, 1024))
      ->capture_default_str();
  cmd->add_option("--dfg-size", opts->dfgSize, "DFG table size")
      ->check(numberIn(2, 4096))
      ->capture_default_str();
  cmd->add_option("--dfg-samples", opts->dfgSamples, "Integration points per DFG texel")
      ->check(numberIn(1, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--sh-window", opts->shWindow,
                  "Window the SH9 coefficients against ringing: lanczos (the sigma factors 1, "
                  "0.827, 0.414), cmgen (Filament cmgen's default --sh-window=auto: the widest "
                  "sinc^4 window whose irradiance stays >= 0) or off (exact)")
      ->check(CLI::IsMember({"off", "lanczos", "cmgen"}))
      ->capture_default_str();
  cmd->add_option("--rotate", opts->rotate, "Rotate the environment about +Y by DEG degrees")
      ->check(finiteNumber())
      ->capture_default_str();
  cmd->add_option("--clamp", opts->clamp,
                  "Clamp the source's radiance to MAX before baking (the power removed is "
                  "reported and recorded in the manifest)")
      ->check(positiveNumber());
  addEnvScaleOptions(cmd, opts->envScale);
  cmd->add_option("--format", opts->format, "KTX2 texel format of the cube maps")
      ->check(CLI::IsMember({"rgba16f", "rgba32f", "b10g11r11", "e5b9g9r9"}))
      ->capture_default_str();
  cmd->add_flag("--exr", opts->exr, "Also write EXR files");
  cmd->add_flag("--hdr", opts->hdr, "Also write Radiance HDR files");
  cmd->add_option("--layout", opts->layout,
                  "Layout of the EXR/HDR copies: a cross, a strip, six faces, or equirect "
                  "(resampled, 4n x 2n for an n^2 level)")
      ->check(CLI::IsMember({"hcross", "vcross", "hstrip", "vstrip", "faces", "equirect"}))
      ->capture_default_str();
  cmd->add_flag("--force", opts->force,
                "Write into an existing, non-empty OUTDIR: replace the earlier bake's files "
                "(and remove those it listed that this bake does not write); keep others");
  cmd->add_flag("--no-preview", opts->noPreview, "Skip the PNG previews");
  cmd->add_flag("--extract-sun", opts->extractSun,
                "Take the sun (the brightest compact source) out of the HDRI, fill its disk from "
                "the sky around it, and list it in the manifest as a sun light (lux)");
  cmd->add_option("--preview-size", opts->previewSize,
                  "Pixels per sphere of preview.png (6 x 2 spheres: 6N x 2N)")
      ->check(numberIn(8, 1024))
      ->capture_default_str();
  return cmd;
}

}  // namespace ibl::cli
