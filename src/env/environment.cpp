#include "ibl/env/environment.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/env/equirect.hpp"
#include "ibl/env/resample.hpp"
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
    case Layout::HStrip:
      return "hstrip";
    case Layout::VStrip:
      return "vstrip";
    case Layout::MirrorBall:
      return "mirrorball";
    case Layout::Angular:
      return "angular";
  }
  return "?";
}

std::optional<Layout> parseLayout(std::string_view name) {
  for (auto l : {Layout::Equirect, Layout::HCross, Layout::VCross, Layout::Faces, Layout::Cube,
                 Layout::HStrip, Layout::VStrip, Layout::MirrorBall, Layout::Angular})
    if (name == layoutName(l)) return l;
  if (name == "cross") return Layout::HCross;
  return std::nullopt;
}

std::optional<Layout> layoutFromShape(int w, int h) {
  if (w == 2 * h) return Layout::Equirect;
  if (w % 4 == 0 && 3 * w == 4 * h) return Layout::HCross;
  if (h % 4 == 0 && 4 * w == 3 * h) return Layout::VCross;
  if (w == 6 * h) return Layout::HStrip;
  if (h == 6 * w) return Layout::VStrip;
  return std::nullopt;
}

namespace {
struct CrossCell {
  int col, row;
  bool rotated;  // stored rotated by 180 degrees
};
// Cell of each face (+X, -X, +Y, -Y, +Z, -Z) in a cross or strip.
CrossCell layoutCell(int face, Layout layout) {
  static constexpr CrossCell kHorizontal[6] = {{2, 1, false}, {0, 1, false}, {1, 0, false},
                                               {1, 2, false}, {1, 1, false}, {3, 1, false}};
  static constexpr CrossCell kVertical[6] = {{2, 1, false}, {0, 1, false}, {1, 0, false},
                                             {1, 2, false}, {1, 1, false}, {1, 3, true}};
  if (layout == Layout::HStrip) return {face, 0, false};
  if (layout == Layout::VStrip) return {0, face, false};
  return layout == Layout::VCross ? kVertical[face] : kHorizontal[face];
}

// Columns and rows of cells of a cross or strip.
std::pair<int, int> layoutCells(Layout layout) {
  switch (layout) {
    case Layout::VCross:
      return {3, 4};
    case Layout::HStrip:
      return {6, 1};
    case Layout::VStrip:
      return {1, 6};
    default:
      return {4, 3};
  }
}
}  // namespace

bool crossGapsAreEmpty(const Image& image, Layout layout) {
  if (layout != Layout::HCross && layout != Layout::VCross) return true;
  const auto [cols, rows] = layoutCells(layout);
  const int cw = image.width / cols, ch = image.height / rows;
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col) {
      bool face = false;
      for (int f = 0; f < kFaceCount; ++f) {
        const CrossCell c = layoutCell(f, layout);
        face = face || (c.col == col && c.row == row);
      }
      if (face) continue;
      for (int y = row * ch; y < (row + 1) * ch; ++y)
        for (int x = col * cw; x < (col + 1) * cw; ++x)
          if (image.at(x, y) != glm::vec3(0.0f)) return false;
    }
  return true;
}

CubeMap cubeFromFlat(const Image& flat, Layout layout, std::string_view name) {
  const auto [cols, rows] = layoutCells(layout);
  if (flat.width % cols != 0 || flat.height % rows != 0 || flat.width / cols != flat.height / rows)
    fail(name, fmt::format("{}x{} is not a {} ({}:{})", flat.width, flat.height, layoutName(layout),
                           cols, rows));
  const int n = flat.width / cols;
  CubeMap cube;
  cube.levels.resize(1);
  for (int f = 0; f < kFaceCount; ++f) {
    const CrossCell c = layoutCell(f, layout);
    Image face = cropImage(flat, c.col * n, c.row * n, n, n);
    cube.levels[0][f] = c.rotated ? rotateImage180(face) : std::move(face);
  }
  return cube;
}

CubeMap cubeFromCross(const Image& cross, bool vertical, std::string_view name) {
  return cubeFromFlat(cross, vertical ? Layout::VCross : Layout::HCross, name);
}

Image flatFromCube(const CubeMap& cube, int level, Layout layout) {
  const int n = cube.levels[level][0].width;
  if (layout == Layout::Equirect) {
    Environment env;
    env.layout = Layout::Cube;
    env.cube.levels = {cube.levels[level]};
    return resampleToEquirect(env, 4 * n);
  }
  const auto [cols, rows] = layoutCells(layout);
  Image out(cols * n, rows * n);
  for (int f = 0; f < kFaceCount; ++f) {
    const CrossCell c = layoutCell(f, layout);
    const Image face = c.rotated ? rotateImage180(cube.levels[level][f]) : cube.levels[level][f];
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) out.at(c.col * n + x, c.row * n + y) = face.at(x, y);
  }
  return out;
}

Image crossFromCube(const CubeMap& cube, int level, bool vertical) {
  return flatFromCube(cube, level, vertical ? Layout::VCross : Layout::HCross);
}

glm::vec2 probeCoordinates(Layout layout, glm::vec3 d) {
  d = glm::normalize(d);
  const float rho = std::sqrt(d.x * d.x + d.y * d.y);
  const float angle = std::acos(std::clamp(d.z, -1.0f, 1.0f));  // from +Z
  // Mirror ball: the normal is halfway between the view's reverse (+Z) and d, r = sin(angle/2);
  // angular map: r = angle / pi.
  const float r = layout == Layout::MirrorBall ? std::sin(0.5f * angle) : angle / 3.14159265358979f;
  const float x = rho > 0.0f ? r * d.x / rho : 0.0f, y = rho > 0.0f ? r * d.y / rho : 0.0f;
  return {0.5f * (x + 1.0f), 0.5f * (1.0f - y)};
}

namespace {

// A panorama (2W x W) of a W x W mirror-ball or angular image: each pixel a bilinear lookup
// where its center's direction is seen.
Image equirectFromProbe(const Image& probe, Layout layout) {
  const int w = 2 * probe.width, h = probe.width;
  Image out(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec3 d =
          equirectToDirection((static_cast<float>(x) + 0.5f) / static_cast<float>(w),
                              (static_cast<float>(y) + 0.5f) / static_cast<float>(h));
      const glm::vec2 uv = probeCoordinates(layout, d);
      const float fx = uv.x * static_cast<float>(probe.width) - 0.5f;
      const float fy = uv.y * static_cast<float>(probe.height) - 0.5f;
      const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
      const float tx = fx - static_cast<float>(x0), ty = fy - static_cast<float>(y0);
      const auto at = [&](int px, int py) {
        return probe.at(std::clamp(px, 0, probe.width - 1), std::clamp(py, 0, probe.height - 1));
      };
      out.at(x, y) = glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), tx),
                              glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), tx), ty);
    }
  return out;
}

}  // namespace

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
                           "or 3:4 cross, 6:1 or 1:6 strip); name one with --input-layout (a "
                           "square image may be a mirrorball or an angular map)",
                           img.width, img.height));
  env.layout = *layout;
  if (*layout == Layout::Equirect) {
    if (img.width < 2) fail(name, "image too small for an environment");
    env.equirect = std::move(img);
  } else if (*layout == Layout::MirrorBall || *layout == Layout::Angular) {
    if (img.width != img.height)
      fail(name, fmt::format("a {} image must be square, not {}x{}", layoutName(*layout), img.width,
                             img.height));
    if (img.width < 2) fail(name, "image too small for an environment");
    env.equirect = equirectFromProbe(img, *layout);
  } else {
    env.cube = cubeFromFlat(img, *layout, name);
  }
  return env;
}

namespace {

// Finds (or repairs) the damage of the pixels as read, then replaces what is not finite,
// non-negative radiance by 0.
void checkDamageAndSanitize(LoadedEnvironment& out, const LoadOptions& options) {
  if (options.repairDamage) {
    DamageRepair repair = repairPixelDamage(out.environment);
    out.damage = repair.damage;
    if (!repair.damage.empty()) out.repair = std::move(repair);
  } else {
    out.damage = findPixelDamage(out.environment);
  }
  out.replaced = sanitizeEnvironment(out.environment);
}

}  // namespace

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
    checkDamageAndSanitize(out, options);
    return out;
  }
  return loadEnvironment(readImageFile(path, {options.layer}), path, options);
}

LoadedEnvironment loadEnvironment(DecodedFile&& d, std::string_view name,
                                  const LoadOptions& options) {
  LoadedEnvironment out;
  out.format = fileFormatName(d.format);
  out.environment = environmentFromFile(std::move(d), options, name);
  checkDamageAndSanitize(out, options);
  return out;
}

LoadedEnvironment loadEnvironmentFromMemory(std::span<const std::uint8_t> bytes,
                                            std::string_view name, const LoadOptions& options) {
  return loadEnvironment(decodeImageFile(bytes, name, {options.layer}), name, options);
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
