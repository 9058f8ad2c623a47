// `ibl convert`: any supported environment in, any layout and format out.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>

#include "batch.hpp"
#include "commands.hpp"
#include "ibl/core/error.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/export.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "preflight.hpp"

namespace ibl::cli {

namespace {

struct ConvertOptions {
  std::vector<std::string> inputs;
  std::string list;         // --list FILE: more inputs
  std::string output;       // of a batch: a pattern with {name}
  std::string layout;       // output layout; empty: default for the output format
  std::string inputLayout;  // empty: detect
  std::string layer;        // EXR layer
  int size = 0;             // 0: keep the source's resolution
  std::string format = "rgba16f";
  std::string exrType = "half";
  float exposure = 0.0f;
  float rotate = 0.0f;
  bool mips = false;
  bool extractSun = false;
  bool repairDamage = false;
  std::string sunJson;
  EnvScaleOptions envScale;  // --env-intensity, --env-illuminance: the pixels written are scaled
};

// Converts `input` into `output`; returns the summary line.
std::string convertOne(const ConvertOptions& o, const std::string& input, const std::string& output,
                       const GlobalOptions& global) {
  ExportOptions e;
  e.output = output;
  if (!o.layout.empty()) e.layout = parseLayout(o.layout);
  e.size = o.size;
  e.ktx2Format = *parsePixelFormat(o.format);
  e.exrType = o.exrType == "float" ? ExrPixelType::Float : ExrPixelType::Half;
  e.pngExposure = o.exposure;
  e.rotateDegrees = o.rotate;
  e.mips = o.mips;
  e.warn = [&](const std::string& message) {
    if (!global.quiet) fmt::print(stderr, "ibl: warning: {}\n", message);
  };
  // Contradictions are reported before the input is read.
  const FileFormat format = checkExportOptions(e);
  if (format != FileFormat::Ktx2 && o.format != "rgba16f")
    failUsage(output, "--format applies to KTX2 outputs only");
  if (format != FileFormat::Exr && o.exrType != "half")
    failUsage(output, "--exr-type applies to EXR outputs only");
  if (format != FileFormat::Png && o.exposure != 0.0f)
    failUsage(output, "--exposure applies to PNG outputs only (the others store linear radiance)");
  std::vector<std::filesystem::path> outputs = possibleExportPaths(e);
  if (!o.sunJson.empty()) outputs.emplace_back(o.sunJson);
  refuseOverwritingInputs(outputs, filesOfInput(input));
  for (const std::filesystem::path& path : outputs) requireWritableFile(path);
  requireReadable(input);
  std::optional<Layout> inLayout;
  if (!o.inputLayout.empty()) inLayout = parseLayout(o.inputLayout);

  // A plain image that is no environment layout (a rendered frame, a lookup table) is
  // converted as a 2D image when no layout is asked.
  const bool mayBeFlat = o.layout.empty() && !inLayout && !o.extractSun && !o.repairDamage &&
                         !isSkySpec(input) && !o.envScale.given() &&
                         input.find("{face}") == std::string::npos;
  const LoadOptions loadOptions{inLayout, o.layer, o.repairDamage};
  SourceEnvironment source;
  if (mayBeFlat) {
    DecodedFile decoded = readImageFile(input, {o.layer});
    const Image& first = decoded.levels[0][0];
    // A 4:3 frame is a cross's shape; a cross leaves its cells outside the cross empty.
    const std::optional<Layout> shape = layoutFromShape(first.width, first.height);
    const bool crossShaped = shape == Layout::HCross || shape == Layout::VCross;
    if (decoded.levels[0].size() == 1 && (!shape || !crossGapsAreEmpty(first, *shape))) {
      Image image = std::move(decoded.levels[0][0]);
      warnAboutReplacedPixels(input, sanitizePixels(image), global);
      const std::vector<EncodedFile> files = encodeFlatImage(image, e);
      writeFilesTogether(files);
      return fmt::format(
          "wrote {} ({} bytes; a {}x{} image, not an environment{})", files[0].path.string(),
          files[0].bytes.size(), image.width, image.height,
          crossShaped ? fmt::format(": a cross's shape, its cells outside the cross not empty; "
                                    "--input-layout {} reads it as one",
                                    layoutName(*shape))
                      : "");
    }
    source.name = input;
    source.loaded = loadEnvironment(std::move(decoded), input, loadOptions);
    reportLoadedPixels(input, source.loaded, global);
  } else {
    source = loadSourceEnvironment(input, loadOptions, o.extractSun, global);
  }
  if (o.envScale.given()) {
    requireLight(source.loaded.environment, source.name);
    scaleSourceEnvironment(source, o.envScale, global);
  }
  std::vector<EncodedFile> files = encodeEnvironment(source.loaded.environment, e);
  if (!o.sunJson.empty()) {
    std::string text = "{\"lights\": [";
    for (std::size_t i = 0; i < source.lights.size(); ++i)
      text += (i ? ", " : "") + lightJson(source.lights[i]);
    text += "]}\n";
    files.push_back({o.sunJson, std::vector<std::uint8_t>(text.begin(), text.end())});
  }
  // All files or none: an error (a full disk) leaves nothing behind.
  writeFilesTogether(files);
  std::string line;
  for (const auto& [path, bytes] : files)
    line +=
        fmt::format("{}wrote {} ({} bytes)", line.empty() ? "" : "\n", path.string(), bytes.size());
  return line;
}

void runConvert(const ConvertOptions& o, const GlobalOptions& global) {
  if (o.inputs.empty() && o.list.empty()) throw CLI::RequiredError("an input (or --list FILE)");
  checkEnvScaleOptions(o.envScale);
  if (o.extractSun)
    for (const std::string& input : o.inputs)
      if (isSkySpec(input))
        failUsage("--extract-sun",
                  fmt::format("contradicts {}: a sky's sun is a light already", input));
  if (o.repairDamage)
    for (const std::string& input : o.inputs)
      if (isSkySpec(input))
        failUsage("--repair-damage",
                  fmt::format("contradicts {}: a computed sky has no damaged pixels", input));
  if (o.extractSun && o.sunJson.empty())
    failUsage("--extract-sun", "needs --sun-json FILE: where the sun taken out of the image goes");
  if (!o.sunJson.empty() && !o.extractSun && !isSkySpec(o.inputs.empty() ? "" : o.inputs[0]))
    failUsage("--sun-json", "applies with --extract-sun or a sky: input (the sun it brings)");
  const bool batch =
      o.inputs.size() > 1 || !o.list.empty() || o.output.find("{name}") != std::string::npos;
  if (!batch) {
    const std::string line = convertOne(o, o.inputs.at(0), o.output, global);
    if (!global.quiet) fmt::print(stderr, "{}\n", line);
    return;
  }
  if (o.output.find("{name}") == std::string::npos)
    failUsage(o.output, "several inputs need {name} in the output (out/{name}.ktx2)");
  if (!o.sunJson.empty()) failUsage("--sun-json", "takes one input, not a batch");
  const std::vector<std::string> inputs = expandInputs(o.inputs, o.list);
  for (const std::string& input : inputs) requireReadable(input);
  runBatch(
      inputs,
      [&](const std::string& input) {
        std::string output = o.output;
        for (auto at = output.find("{name}"); at != std::string::npos; at = output.find("{name}"))
          output.replace(at, 6, batchName(input));
        return convertOne(o, input, output, global);
      },
      true, global);
}

}  // namespace

void addConvertCommand(CLI::App& app, const GlobalOptions& global) {
  auto opts = std::make_shared<ConvertOptions>();
  CLI::App* cmd = app.add_subcommand(
      "convert", "Convert an environment between formats (hdr, exr, png, jpg, ktx2) and layouts");
  cmd->add_option("inputs", opts->inputs,
                  "Input files; a path with {face} names six face files (px nx py ny pz nz); "
                  "a quoted pattern such as 'hdri/*.exr' is expanded; or a physical sky, "
                  "sky:elevation=30,azimuth=120 (see ibl sky)");
  cmd->add_option("--list", opts->list,
                  "Also convert the files this text file lists, one per line (a batch)");
  cmd->add_option("-o,--output", opts->output,
                  "Output file (.ktx2, .exr, .hdr, .png); with --layout faces, {face} in the "
                  "name is replaced, else _px.. is appended. Several inputs: {name} in it is "
                  "each input's name (out/{name}.ktx2). Missing folders are created")
      ->required();
  const auto layouts =
      CLI::IsMember({"equirect", "cube", "cross", "hcross", "vcross", "hstrip", "vstrip", "faces"});
  cmd->add_option("--layout", opts->layout,
                  "Output layout (default: cube for .ktx2, else equirect for equirect inputs "
                  "and hcross for cube inputs)")
      ->check(layouts);
  cmd->add_option("--input-layout", opts->inputLayout,
                  "Input layout (default: detected from the image shape)")
      ->check(CLI::IsMember({"equirect", "cross", "hcross", "vcross", "hstrip", "vstrip", "faces",
                             "mirrorball", "angular"}));
  cmd->add_option("--layer", opts->layer,
                  "EXR layer to read (ViewLayer.Combined); default: the plain R, G, B channels or "
                  "the only color layer");
  cmd->add_option("--size", opts->size,
                  "Cube face size, or equirect width (default: the source's resolution)")
      ->check(numberIn(1, 16384));
  cmd->add_option("--format", opts->format, "KTX2 texel format")
      ->check(CLI::IsMember({"rgba16f", "rgba32f", "b10g11r11", "e5b9g9r9"}))
      ->capture_default_str();
  cmd->add_option("--exr-type", opts->exrType, "EXR pixel type")
      ->check(CLI::IsMember({"half", "float"}))
      ->capture_default_str();
  cmd->add_option("--exposure", opts->exposure, "PNG exposure in stops (scale by 2^EV)")
      ->check(finiteNumber())
      ->capture_default_str();
  cmd->add_option("--rotate", opts->rotate,
                  "Rotate the environment about +Y by DEG degrees (+X turns toward -Z)")
      ->check(finiteNumber())
      ->capture_default_str();
  addEnvScaleOptions(cmd, opts->envScale);
  cmd->add_flag("--mips", opts->mips,
                "Write the full mip chain of a cube map (one KTX2, or _m<level> files)");
  cmd->add_flag("--extract-sun", opts->extractSun,
                "Take the sun (the brightest compact source) out of the image, fill its disk "
                "from the sky around it, and write it with --sun-json");
  cmd->add_flag("--repair-damage", opts->repairDamage,
                "Replace damaged pixels (a block whose channels contradict their neighbourhood by "
                "orders of magnitude, as lossy EXR compression leaves them; `ibl info` lists "
                "them) by their undamaged neighbourhood, and print how much the environment's "
                "power changed");
  cmd->add_option("--sun-json", opts->sunJson,
                  "Write the extracted sun (or a sky: input's sun) as a lights file for --lights "
                  "(missing folders are created)");
  cmd->callback([opts, &global] { runConvert(*opts, global); });
}

}  // namespace ibl::cli
