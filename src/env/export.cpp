#include "ibl/env/export.hpp"

#include <bit>

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/env/resample.hpp"

namespace ibl {

namespace fs = std::filesystem;

namespace {

fs::path levelPath(const fs::path& p, int level, bool suffix) {
  if (!suffix) return p;
  fs::path out = p;
  const std::string ext = out.extension().string();
  out.replace_extension();
  out += fmt::format("_m{}{}", level, ext);
  return out;
}

std::vector<std::uint8_t> encodeFlat(const Image& img, FileFormat format, const ExportOptions& o) {
  switch (format) {
    case FileFormat::Hdr:
      return encodeHdr(img);
    case FileFormat::Exr:
      return encodeExr(img, o.exrType);
    case FileFormat::Png:
      return encodePng(img, o.pngExposure);
    default:
      fail(o.output.string(), "cannot write this format as a flat image");
  }
}

// The layout to write: the one asked for, or the default for the format and the source.
Layout outputLayout(const Environment& env, FileFormat format, const ExportOptions& o) {
  if (o.layout) return *o.layout;
  if (format == FileFormat::Ktx2) return Layout::Cube;
  return env.isCube() ? Layout::HCross : Layout::Equirect;
}

std::vector<EncodedFile> encodeEquirect(const Environment& env, FileFormat format,
                                        const ExportOptions& o) {
  if (o.mips) fail(o.output.string(), "--mips applies to cube map outputs only");
  const int width = o.size > 0 ? o.size : (env.isCube() ? 4 * env.cube.size() : env.equirect.width);
  if (width % 2 != 0) fail(o.output.string(), "equirect width (--size) must be even");
  const bool same = !env.isCube() && width == env.equirect.width && o.rotateDegrees == 0.0f;
  const Image img = same ? env.equirect : resampleToEquirect(env, width, o.rotateDegrees);
  if (format == FileFormat::Ktx2) {
    Ktx2Texture tex;
    tex.format = o.ktx2Format;
    tex.levels = {{img}};
    return {{o.output, encodeKtx2(tex)}};
  }
  return {{o.output, encodeFlat(img, format, o)}};
}

std::vector<EncodedFile> encodeCube(const Environment& env, FileFormat format, Layout layout,
                                    const ExportOptions& o) {
  const int size = o.size > 0 ? o.size : defaultCubeSize(env);
  if (o.mips && !std::has_single_bit(static_cast<unsigned>(size)))
    fail(o.output.string(), fmt::format("--mips needs a power-of-two size, not {}", size));
  CubeMap cube;
  if (env.isCube() && size == env.cube.size() && o.rotateDegrees == 0.0f) {
    cube.levels = {env.cube.levels[0]};
  } else {
    cube = resampleToCube(env, size, o.rotateDegrees);
  }
  if (o.mips) buildMipChain(cube);
  if (format == FileFormat::Ktx2) return {{o.output, encodeKtx2(cubeTexture(cube, o.ktx2Format))}};
  std::vector<EncodedFile> files;
  for (int m = 0; m < cube.levelCount(); ++m) {
    const fs::path path = levelPath(o.output, m, o.mips);
    if (layout == Layout::Faces) {
      for (int f = 0; f < kFaceCount; ++f)
        files.push_back({facePath(path, f), encodeFlat(cube.levels[m][f], format, o)});
    } else {
      files.push_back(
          {path, encodeFlat(crossFromCube(cube, m, layout == Layout::VCross), format, o)});
    }
  }
  return files;
}

}  // namespace

Ktx2Texture cubeTexture(const CubeMap& cube, PixelFormat format) {
  Ktx2Texture tex;
  tex.format = format;
  tex.faceCount = kFaceCount;
  for (const auto& level : cube.levels) tex.levels.emplace_back(level.begin(), level.end());
  return tex;
}

int defaultCubeSize(const Environment& env) {
  if (env.isCube()) return env.cube.size();
  return std::max(1,
                  static_cast<int>(std::bit_floor(static_cast<unsigned>(env.equirect.width / 4))));
}

FileFormat checkExportOptions(const ExportOptions& o) {
  const std::string out = o.output.string();
  const auto format = fileFormatFromExtension(o.output);
  if (!format || *format == FileFormat::Jpg)
    fail(out, "unknown output format (use .ktx2, .exr, .hdr or .png)");
  if (o.layout && *format == FileFormat::Ktx2 && *o.layout != Layout::Cube &&
      *o.layout != Layout::Equirect)
    fail(out, "KTX2 holds cube maps (--layout cube) or 2D equirect images");
  if (o.layout && *format != FileFormat::Ktx2 && *o.layout == Layout::Cube)
    fail(out, "--layout cube needs a .ktx2 output; use hcross, vcross or faces");
  return *format;
}

std::vector<EncodedFile> encodeEnvironment(const Environment& env, const ExportOptions& o) {
  const FileFormat format = checkExportOptions(o);
  const Layout layout = outputLayout(env, format, o);
  return layout == Layout::Equirect ? encodeEquirect(env, format, o)
                                    : encodeCube(env, format, layout, o);
}

}  // namespace ibl
