// `ibl convert`: any supported environment in, any layout and format out.
#include <bit>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>

#include "commands.hpp"
#include "ibl/core/error.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/ktx2.hpp"

namespace ibl::cli {

namespace {

struct ConvertOptions {
  std::string input;
  std::string output;
  std::string layout;       // output layout; empty: default for the output format
  std::string inputLayout;  // empty: detect
  int size = 0;             // 0: keep the source's resolution
  std::string format = "rgba16f";
  std::string exrType = "half";
  float exposure = 0.0f;
  float rotate = 0.0f;
  bool mips = false;
};

std::filesystem::path levelPath(const std::filesystem::path& p, int level, bool suffix) {
  if (!suffix) return p;
  std::filesystem::path out = p;
  const std::string ext = out.extension().string();
  out.replace_extension();
  out += fmt::format("_m{}{}", level, ext);
  return out;
}

std::vector<std::uint8_t> encodeFlat(const Image& img, FileFormat format, const ConvertOptions& o) {
  switch (format) {
    case FileFormat::Hdr:
      return encodeHdr(img);
    case FileFormat::Exr:
      return encodeExr(img, o.exrType == "float" ? ExrPixelType::Float : ExrPixelType::Half);
    case FileFormat::Png:
      return encodePng(img, o.exposure);
    default:
      fail(o.output, "cannot write this format as a flat image");
  }
}

// Default output size: match the angular resolution of the source.
int defaultCubeSize(const Environment& env) {
  if (env.isCube()) return env.cube.size();
  return std::max(1,
                  static_cast<int>(std::bit_floor(static_cast<unsigned>(env.equirect.width / 4))));
}

void runConvert(const ConvertOptions& o, const GlobalOptions& global) {
  const auto outFormat = fileFormatFromExtension(o.output);
  if (!outFormat || *outFormat == FileFormat::Jpg)
    fail(o.output, "unknown output format (use .ktx2, .exr, .hdr or .png)");
  std::optional<Layout> inLayout;
  if (!o.inputLayout.empty()) inLayout = parseLayout(o.inputLayout);

  Layout layout;
  if (!o.layout.empty()) {
    layout = *parseLayout(o.layout);
  } else if (*outFormat == FileFormat::Ktx2) {
    layout = Layout::Cube;
  } else {
    layout = Layout::Equirect;  // refined below once the input is known
  }
  const bool layoutGiven = !o.layout.empty();
  if (*outFormat == FileFormat::Ktx2 && layout != Layout::Cube && layout != Layout::Equirect)
    fail(o.output, "KTX2 holds cube maps (--layout cube) or 2D equirect images");
  if (*outFormat != FileFormat::Ktx2 && layout == Layout::Cube)
    fail(o.output, "--layout cube needs a .ktx2 output; use hcross, vcross or faces");
  if (*outFormat != FileFormat::Ktx2 && o.format != "rgba16f")
    fail(o.output, "--format applies to KTX2 outputs only");
  if (*outFormat != FileFormat::Exr && o.exrType != "half")
    fail(o.output, "--exr-type applies to EXR outputs only");

  LoadedEnvironment loaded = loadEnvironment(o.input, {inLayout});
  const Environment& env = loaded.environment;
  if (loaded.replaced.total() > 0 && !global.quiet)
    fmt::print(stderr,
               "ibl: warning: {}: replaced {} NaN, {} infinite and {} negative pixel components "
               "by 0\n",
               o.input, loaded.replaced.nan, loaded.replaced.infinite, loaded.replaced.negative);
  if (!layoutGiven && *outFormat != FileFormat::Ktx2 && env.isCube()) layout = Layout::HCross;

  std::vector<std::pair<std::filesystem::path, std::vector<std::uint8_t>>> files;
  if (layout == Layout::Equirect) {
    if (o.mips) fail(o.output, "--mips applies to cube map outputs only");
    const int width =
        o.size > 0 ? o.size : (env.isCube() ? 4 * env.cube.size() : env.equirect.width);
    if (width % 2 != 0) fail(o.output, "equirect width (--size) must be even");
    const bool same = !env.isCube() && width == env.equirect.width && o.rotate == 0.0f;
    const Image img = same ? env.equirect : resampleToEquirect(env, width, o.rotate);
    if (*outFormat == FileFormat::Ktx2) {
      Ktx2Texture tex;
      tex.format = *parsePixelFormat(o.format);
      tex.levels = {{img}};
      files.emplace_back(o.output, encodeKtx2(tex));
    } else {
      files.emplace_back(o.output, encodeFlat(img, *outFormat, o));
    }
  } else {
    const int size = o.size > 0 ? o.size : defaultCubeSize(env);
    if (o.mips && !std::has_single_bit(static_cast<unsigned>(size)))
      fail(o.output, fmt::format("--mips needs a power-of-two size, not {}", size));
    CubeMap cube;
    if (env.isCube() && size == env.cube.size() && o.rotate == 0.0f) {
      cube.levels = {env.cube.levels[0]};
    } else {
      cube = resampleToCube(env, size, o.rotate);
    }
    if (o.mips) buildMipChain(cube);
    if (*outFormat == FileFormat::Ktx2) {
      Ktx2Texture tex;
      tex.format = *parsePixelFormat(o.format);
      tex.faceCount = kFaceCount;
      for (const auto& level : cube.levels) tex.levels.emplace_back(level.begin(), level.end());
      files.emplace_back(o.output, encodeKtx2(tex));
    } else {
      for (int m = 0; m < cube.levelCount(); ++m) {
        const auto path = levelPath(o.output, m, o.mips);
        if (layout == Layout::Faces) {
          for (int f = 0; f < kFaceCount; ++f)
            files.emplace_back(facePath(path, f), encodeFlat(cube.levels[m][f], *outFormat, o));
        } else {
          files.emplace_back(
              path, encodeFlat(crossFromCube(cube, m, layout == Layout::VCross), *outFormat, o));
        }
      }
    }
  }
  // Everything is encoded before the first file is written: an error leaves nothing behind.
  for (const auto& [path, bytes] : files) {
    writeFileAtomic(path, bytes);
    if (!global.quiet) fmt::print(stderr, "wrote {} ({} bytes)\n", path.string(), bytes.size());
  }
}

}  // namespace

void addConvertCommand(CLI::App& app, const GlobalOptions& global) {
  auto opts = std::make_shared<ConvertOptions>();
  CLI::App* cmd = app.add_subcommand(
      "convert", "Convert an environment between formats (hdr, exr, png, jpg, ktx2) and layouts");
  cmd->add_option("input", opts->input,
                  "Input file; a path with {face} names six face files (px nx py ny pz nz)")
      ->required();
  cmd->add_option("-o,--output", opts->output,
                  "Output file (.ktx2, .exr, .hdr, .png); with --layout faces, {face} in the "
                  "name is replaced, else _px.. is appended")
      ->required();
  const auto layouts = CLI::IsMember({"equirect", "cube", "cross", "hcross", "vcross", "faces"});
  cmd->add_option("--layout", opts->layout,
                  "Output layout (default: cube for .ktx2, else equirect for equirect inputs "
                  "and hcross for cube inputs)")
      ->check(layouts);
  cmd->add_option("--input-layout", opts->inputLayout,
                  "Input layout (default: detected from the image shape)")
      ->check(CLI::IsMember({"equirect", "cross", "hcross", "vcross", "faces"}));
  cmd->add_option("--size", opts->size,
                  "Cube face size, or equirect width (default: the source's resolution)")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--format", opts->format, "KTX2 texel format")
      ->check(CLI::IsMember({"rgba16f", "rgba32f", "b10g11r11", "e5b9g9r9"}))
      ->capture_default_str();
  cmd->add_option("--exr-type", opts->exrType, "EXR pixel type")
      ->check(CLI::IsMember({"half", "float"}))
      ->capture_default_str();
  cmd->add_option("--exposure", opts->exposure, "PNG exposure in stops (scale by 2^EV)")
      ->capture_default_str();
  cmd->add_option("--rotate", opts->rotate,
                  "Rotate the environment about +Y by DEG degrees (+X turns toward -Z)")
      ->capture_default_str();
  cmd->add_flag("--mips", opts->mips,
                "Write the full mip chain of a cube map (one KTX2, or _m<level> files)");
  cmd->callback([opts, &global] { runConvert(*opts, global); });
}

}  // namespace ibl::cli
