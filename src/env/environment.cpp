#include "ibl/env/environment.hpp"

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/io/image_io.hpp"

namespace ibl {

std::string_view layoutName(Layout l) {
  switch (l) {
    case Layout::Equirect:
      return "equirect";
    case Layout::HCross:
      return "hcross";
    case Layout::VCross:
      return "vcross";
    case Layout::Faces:
      return "faces";
    case Layout::Cube:
      return "cube";
  }
  return "?";
}

std::optional<Layout> parseLayout(std::string_view name) {
  for (auto l : {Layout::Equirect, Layout::HCross, Layout::VCross, Layout::Faces, Layout::Cube})
    if (name == layoutName(l)) return l;
  if (name == "cross") return Layout::HCross;
  return std::nullopt;
}

std::optional<Layout> layoutFromShape(int w, int h) {
  if (w == 2 * h) return Layout::Equirect;
  if (w % 4 == 0 && 3 * w == 4 * h) return Layout::HCross;
  if (h % 4 == 0 && 4 * w == 3 * h) return Layout::VCross;
  return std::nullopt;
}

namespace {
struct CrossCell {
  int col, row;
  bool rotated;  // stored rotated by 180 degrees
};
// Cell of each face (+X, -X, +Y, -Y, +Z, -Z) in the cross.
CrossCell crossCell(int face, bool vertical) {
  static constexpr CrossCell kHorizontal[6] = {{2, 1, false}, {0, 1, false}, {1, 0, false},
                                               {1, 2, false}, {1, 1, false}, {3, 1, false}};
  static constexpr CrossCell kVertical[6] = {{2, 1, false}, {0, 1, false}, {1, 0, false},
                                             {1, 2, false}, {1, 1, false}, {1, 3, true}};
  return vertical ? kVertical[face] : kHorizontal[face];
}
}  // namespace

CubeMap cubeFromCross(const Image& cross, bool vertical, std::string_view name) {
  const int cols = vertical ? 3 : 4, rows = vertical ? 4 : 3;
  if (cross.width % cols != 0 || cross.height % rows != 0 ||
      cross.width / cols != cross.height / rows)
    fail(name, fmt::format("{}x{} is not a {} cross ({}:{})", cross.width, cross.height,
                           vertical ? "vertical" : "horizontal", cols, rows));
  const int n = cross.width / cols;
  CubeMap cube;
  cube.levels.resize(1);
  for (int f = 0; f < kFaceCount; ++f) {
    const CrossCell c = crossCell(f, vertical);
    Image face = cropImage(cross, c.col * n, c.row * n, n, n);
    cube.levels[0][f] = c.rotated ? rotateImage180(face) : std::move(face);
  }
  return cube;
}

Image crossFromCube(const CubeMap& cube, int level, bool vertical) {
  const int n = cube.levels[level][0].width;
  Image out(vertical ? 3 * n : 4 * n, vertical ? 4 * n : 3 * n);
  for (int f = 0; f < kFaceCount; ++f) {
    const CrossCell c = crossCell(f, vertical);
    const Image face = c.rotated ? rotateImage180(cube.levels[level][f]) : cube.levels[level][f];
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) out.at(c.col * n + x, c.row * n + y) = face.at(x, y);
  }
  return out;
}

std::filesystem::path facePath(const std::filesystem::path& pattern, int face) {
  std::string s = pattern.string();
  const auto at = s.find("{face}");
  if (at != std::string::npos) return s.replace(at, 6, kFaceNames[face]);
  std::filesystem::path p = pattern;
  const std::string ext = p.extension().string();
  p.replace_extension();
  p += fmt::format("_{}{}", kFaceNames[face], ext);
  return p;
}

Environment environmentFromFile(DecodedFile&& d, const LoadOptions& options,
                                std::string_view name) {
  Environment env;
  if (d.levels[0].size() == kFaceCount) {
    if (options.layout && *options.layout != Layout::Cube)
      fail(name, fmt::format("is a cube map, not a {} image", layoutName(*options.layout)));
    env.layout = Layout::Cube;
    for (auto& level : d.levels) {
      env.cube.levels.emplace_back();
      for (int f = 0; f < kFaceCount; ++f) env.cube.levels.back()[f] = std::move(level[f]);
    }
    return env;
  }
  Image& img = d.levels[0][0];
  const auto layout = options.layout ? options.layout : layoutFromShape(img.width, img.height);
  if (!layout || *layout == Layout::Cube || *layout == Layout::Faces)
    fail(name, fmt::format("cannot tell the layout of a {}x{} image (expected 2:1 equirect, 4:3 "
                           "or 3:4 cross); name one with --input-layout",
                           img.width, img.height));
  env.layout = *layout;
  if (*layout == Layout::Equirect) {
    if (img.width < 2) fail(name, "image too small for an environment");
    env.equirect = std::move(img);
  } else {
    env.cube = cubeFromCross(img, *layout == Layout::VCross, name);
  }
  return env;
}

LoadedEnvironment loadEnvironment(const std::string& path, const LoadOptions& options) {
  LoadedEnvironment out;
  Environment& env = out.environment;
  const bool sixFiles = path.find("{face}") != std::string::npos || options.layout == Layout::Faces;
  if (sixFiles) {
    env.layout = Layout::Faces;
    env.cube.levels.resize(1);
    for (int f = 0; f < kFaceCount; ++f) {
      const std::string file = facePath(path, f).string();
      DecodedFile d = readImageFile(file, {options.layer});
      Image& img = d.levels[0][0];
      if (img.width != img.height)
        fail(file, fmt::format("face is {}x{}, not square", img.width, img.height));
      if (f > 0 && img.width != env.cube.levels[0][0].width) fail(file, "faces differ in size");
      out.format = fileFormatName(d.format);
      env.cube.levels[0][f] = std::move(img);
    }
  } else {
    DecodedFile d = readImageFile(path, {options.layer});
    out.format = fileFormatName(d.format);
    env = environmentFromFile(std::move(d), options, path);
  }
  out.replaced = sanitizeEnvironment(env);
  return out;
}

LoadedEnvironment loadEnvironmentFromMemory(std::span<const std::uint8_t> bytes,
                                            std::string_view name, const LoadOptions& options) {
  LoadedEnvironment out;
  DecodedFile d = decodeImageFile(bytes, name, {options.layer});
  out.format = fileFormatName(d.format);
  out.environment = environmentFromFile(std::move(d), options, name);
  out.replaced = sanitizeEnvironment(out.environment);
  return out;
}

InvalidPixelCounts sanitizeEnvironment(Environment& env) {
  InvalidPixelCounts replaced;
  if (env.isCube()) {
    for (auto& level : env.cube.levels)
      for (auto& face : level) replaced += sanitizePixels(face);
  } else {
    replaced += sanitizePixels(env.equirect);
  }
  return replaced;
}

}  // namespace ibl
