#include "ibl/env/export.hpp"

#include <bit>

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/env/equirect.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/io/pixel_formats.hpp"
#include "ibl/math/color.hpp"

namespace ibl {

namespace fs = std::filesystem;

namespace {

// Adds one pixel's share to a RangeLoss: weight = its solid angle.
void accumulateLoss(RangeLoss& loss, double& total, glm::vec3 v, glm::vec3 largest, double weight) {
  const glm::vec3 kept = glm::min(v, largest);
  for (int c = 0; c < 3; ++c)
    if (v[c] > largest[c]) {
      ++loss.clamped;
      loss.brightest = std::max(loss.brightest, v[c]);
    }
  total += weight * luminance(glm::max(v, glm::vec3(0.0f)));
  loss.lostPower += weight * luminance(glm::max(v - kept, glm::vec3(0.0f)));
}

RangeLoss finish(RangeLoss loss, double total) {
  loss.lostPower = total > 0.0 ? loss.lostPower / total : 0.0;
  return loss;
}

// Warns about a file whose values the format clamps.
void warnAboutRange(const ExportOptions& o, const fs::path& path, const RangeLoss& loss,
                    std::string_view formatName, float limit) {
  if (!o.warn || loss.clamped == 0) return;
  o.warn(fmt::format("{}: {} by the {} format; write rgba32f or float EXR to keep it",
                     path.string(), describe(loss, limit), formatName));
}

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
  if (format == FileFormat::Ktx2 ||
      (format == FileFormat::Exr && o.exrType == ExrPixelType::Half)) {
    const PixelFormat stored = format == FileFormat::Ktx2 ? o.ktx2Format : PixelFormat::Rgba16f;
    warnAboutRange(o, o.output, rangeLoss(img, largestValue(stored)), formatName(stored),
                   largestValue(stored).x);
  }
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
  if (format == FileFormat::Ktx2 ||
      (format == FileFormat::Exr && o.exrType == ExrPixelType::Half)) {
    const PixelFormat stored = format == FileFormat::Ktx2 ? o.ktx2Format : PixelFormat::Rgba16f;
    warnAboutRange(o, o.output, rangeLoss(cube, largestValue(stored)), formatName(stored),
                   largestValue(stored).x);
  }
  if (format == FileFormat::Ktx2) return {{o.output, encodeKtx2(cubeTexture(cube, o.ktx2Format))}};
  std::vector<EncodedFile> files;
  for (int m = 0; m < cube.levelCount(); ++m) {
    const fs::path path = levelPath(o.output, m, o.mips);
    if (layout == Layout::Faces) {
      for (int f = 0; f < kFaceCount; ++f)
        files.push_back({facePath(path, f), encodeFlat(cube.levels[m][f], format, o)});
    } else {
      files.push_back({path, encodeFlat(flatFromCube(cube, m, layout), format, o)});
    }
  }
  return files;
}

}  // namespace

RangeLoss rangeLoss(const CubeMap& cube, glm::vec3 largest) {
  RangeLoss all;
  for (int m = 0; m < cube.levelCount(); ++m) {
    RangeLoss loss;
    double total = 0.0;
    const int n = cube.levels[m][0].width;
    const std::vector<double> omega = faceTexelSolidAngles(n);
    for (int f = 0; f < kFaceCount; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
          accumulateLoss(loss, total, cube.levels[m][f].at(x, y), largest,
                         omega[static_cast<std::size_t>(y) * n + x]);
    loss = finish(loss, total);
    all.clamped += loss.clamped;
    all.brightest = std::max(all.brightest, loss.brightest);
    all.lostPower = std::max(all.lostPower, loss.lostPower);
  }
  return all;
}

RangeLoss rangeLoss(const Image& equirect, glm::vec3 largest) {
  RangeLoss loss;
  double total = 0.0;
  for (int y = 0; y < equirect.height; ++y) {
    const double omega = equirectPixelSolidAngle(y, equirect.width, equirect.height);
    for (int x = 0; x < equirect.width; ++x)
      accumulateLoss(loss, total, equirect.at(x, y), largest, omega);
  }
  return finish(loss, total);
}

RangeLoss clampEnvironment(Environment& env, float limit) {
  const glm::vec3 largest(limit);
  const RangeLoss loss =
      env.isCube() ? rangeLoss(env.cube, largest) : rangeLoss(env.equirect, largest);
  const auto clampImage = [&](Image& img) {
    for (auto& p : img.pixels) p = glm::min(p, largest);
  };
  if (env.isCube()) {
    for (auto& level : env.cube.levels)
      for (auto& face : level) clampImage(face);
  } else {
    clampImage(env.equirect);
  }
  return loss;
}

std::string describe(const RangeLoss& loss, float limit) {
  return fmt::format("{} value{} above {:g} clamped (brightest {:g}), {:.3g} % of the power lost",
                     loss.clamped, loss.clamped == 1 ? "" : "s", limit, loss.brightest,
                     100.0 * loss.lostPower);
}

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

std::vector<fs::path> possibleExportPaths(const ExportOptions& o) {
  std::vector<fs::path> paths;
  constexpr int kMaxLevels = 17;  // a 65536^2 face down to 1^2
  for (int m = 0; m < (o.mips ? kMaxLevels : 1); ++m) {
    const fs::path path = levelPath(o.output, m, o.mips);
    paths.push_back(path);
    if (o.layout == Layout::Faces)
      for (int f = 0; f < kFaceCount; ++f) paths.push_back(facePath(path, f));
  }
  return paths;
}

std::vector<EncodedFile> encodeFlatImage(const Image& image, const ExportOptions& o) {
  const FileFormat format = checkExportOptions(o);
  const std::string out = o.output.string();
  if (o.layout || o.size > 0 || o.rotateDegrees != 0.0f || o.mips)
    fail(out,
         "--layout, --size, --rotate and --mips apply to environments; the input is a flat "
         "image (name its layout with --input-layout to read it as an environment)");
  if (format == FileFormat::Ktx2 ||
      (format == FileFormat::Exr && o.exrType == ExrPixelType::Half)) {
    const PixelFormat stored = format == FileFormat::Ktx2 ? o.ktx2Format : PixelFormat::Rgba16f;
    const glm::vec3 largest = largestValue(stored);
    std::size_t clamped = 0;
    float brightest = 0.0f;
    for (const glm::vec3& p : image.pixels)
      for (int c = 0; c < 3; ++c)
        if (p[c] > largest[c]) {
          ++clamped;
          brightest = std::max(brightest, p[c]);
        }
    if (clamped > 0 && o.warn)
      o.warn(
          fmt::format("{}: {} values above the {} range clamped (brightest {:g}); write "
                      "rgba32f or float EXR to keep them",
                      out, clamped, formatName(stored), brightest));
  }
  if (format == FileFormat::Ktx2) {
    Ktx2Texture tex;
    tex.format = o.ktx2Format;
    tex.levels = {{image}};
    return {{o.output, encodeKtx2(tex)}};
  }
  return {{o.output, encodeFlat(image, format, o)}};
}

FileFormat checkExportOptions(const ExportOptions& o) {
  const std::string out = o.output.string();
  const auto format = fileFormatFromExtension(o.output);
  if (!format || *format == FileFormat::Jpg)
    failUsage(out, "unknown output format (use .ktx2, .exr, .hdr or .png)");
  if (o.layout && *format == FileFormat::Ktx2 && *o.layout != Layout::Cube &&
      *o.layout != Layout::Equirect)
    failUsage(out, "KTX2 holds cube maps (--layout cube) or 2D equirect images");
  if (o.layout && *format != FileFormat::Ktx2 && *o.layout == Layout::Cube)
    failUsage(out,
              "--layout cube needs a .ktx2 output; use hcross, vcross, hstrip, vstrip or faces");
  if (o.layout && (*o.layout == Layout::MirrorBall || *o.layout == Layout::Angular))
    failUsage(out, fmt::format("--layout {} is an input layout only", layoutName(*o.layout)));
  // What the options alone decide (the source's shape decides the rest, when it is read).
  const bool cubeLayout = o.layout && *o.layout != Layout::Equirect;
  if (o.mips && o.layout == Layout::Equirect)
    failUsage(out, "--mips applies to cube map outputs only");
  if (o.size > 0 && o.layout == Layout::Equirect && o.size % 2 != 0)
    failUsage(out, fmt::format("equirect width (--size) must be even, not {}", o.size));
  if (o.mips && o.size > 0 && (cubeLayout || *format == FileFormat::Ktx2) &&
      !std::has_single_bit(static_cast<unsigned>(o.size)))
    failUsage(out, fmt::format("--mips needs a power-of-two size, not {}", o.size));
  return *format;
}

std::vector<EncodedFile> encodeEnvironment(const Environment& env, const ExportOptions& o) {
  const FileFormat format = checkExportOptions(o);
  const Layout layout = outputLayout(env, format, o);
  return layout == Layout::Equirect ? encodeEquirect(env, format, o)
                                    : encodeCube(env, format, layout, o);
}

}  // namespace ibl
