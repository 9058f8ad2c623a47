#include "ibl/env/pixel_damage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "ibl/core/parallel.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/math/color.hpp"

namespace ibl {

namespace {

constexpr int kTile = 8;           // the neighbourhood's tiles (a DCT block's size)
constexpr float kOrders = 100.0f;  // rule 1: two orders of magnitude each way
constexpr float kRinging = 0.5f;   // rule 2: the negative part allowed of the local peak
constexpr int kPeakRadius = 2;
constexpr float kNoiseFloor = 1e-3f;  // rule 2: f, of the image's mean luminance           // rule
                                      // 2: P_c over the 5 x 5 pixels around
constexpr float kBlockContrast = 10.0f;  // rule 3: one order of magnitude
constexpr int kGrowth = kTile;           // rule 3: at most this many pixels from rules 1, 2

bool usable(float v) {
  return std::isfinite(v);
}

// m per tile: the per-channel median of the pixels at even offsets in the 3 x 3 tiles around.
std::vector<glm::vec3> tileLevels(const Image& image) {
  const int tilesX = (image.width + kTile - 1) / kTile;
  const int tilesY = (image.height + kTile - 1) / kTile;
  std::vector<glm::vec3> levels(static_cast<std::size_t>(tilesX) * tilesY);
  parallelFor(0, tilesY, [&](int ty) {
    std::array<std::vector<float>, 3> samples;
    for (int tx = 0; tx < tilesX; ++tx) {
      for (auto& s : samples) s.clear();
      for (int y = (ty - 1) * kTile; y < (ty + 2) * kTile; y += 2)
        for (int x = (tx - 1) * kTile; x < (tx + 2) * kTile; x += 2) {
          const glm::vec3 v =
              image.at(std::clamp(x, 0, image.width - 1), std::clamp(y, 0, image.height - 1));
          for (int c = 0; c < 3; ++c)
            if (usable(v[c])) samples[c].push_back(v[c]);
        }
      glm::vec3 m(0.0f);
      for (int c = 0; c < 3; ++c) {
        auto& s = samples[c];
        if (s.empty()) continue;
        const auto mid = s.begin() + static_cast<std::ptrdiff_t>(s.size() / 2);
        std::nth_element(s.begin(), mid, s.end());
        m[c] = std::max(*mid, 0.0f);
      }
      levels[static_cast<std::size_t>(ty) * tilesX + tx] = m;
    }
  });
  return levels;
}

// The mean luminance of an image's pixels, negative and non-finite values as 0.
float meanLuminance(const Image& image) {
  double sum = 0.0;
  for (const glm::vec3& p : image.pixels)
    if (usable(p.x) && usable(p.y) && usable(p.z)) sum += luminance(glm::max(p, glm::vec3(0.0f)));
  return image.pixels.empty() ? 0.0f : static_cast<float>(sum / double(image.pixels.size()));
}

// Rule 1: one channel 100 times the neighbourhood's, another a hundredth of it or less.
bool contradictsByOrders(glm::vec3 v, glm::vec3 m) {
  bool up = false, down = false;
  for (int c = 0; c < 3; ++c) {
    if (!usable(v[c])) return false;
    up |= m[c] > 0.0f && v[c] >= kOrders * m[c];
    down |= m[c] > 0.0f && v[c] <= m[c] / kOrders;
  }
  return up && down;
}

// Rule 3: a channel an order of magnitude below the neighbourhood's, or two above it.
bool outOfPlace(glm::vec3 v, glm::vec3 m) {
  for (int c = 0; c < 3; ++c) {
    if (!usable(v[c]) || m[c] <= 0.0f) continue;
    if (v[c] >= kOrders * m[c] || v[c] <= m[c] / kBlockContrast) return true;
  }
  return false;
}

// Rule 2: a channel below -0.5 max(P_c, m_c, f).
bool negativeBeyondNoise(const Image& image, int x, int y, glm::vec3 m, float floor) {
  const glm::vec3 v = image.at(x, y);
  if (!(v.x < 0.0f || v.y < 0.0f || v.z < 0.0f)) return false;
  glm::vec3 peak = glm::max(m, glm::vec3(floor));
  for (int dy = -kPeakRadius; dy <= kPeakRadius; ++dy)
    for (int dx = -kPeakRadius; dx <= kPeakRadius; ++dx) {
      const int px = x + dx, py = y + dy;
      if (px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
      const glm::vec3 p = image.at(px, py);
      for (int c = 0; c < 3; ++c)
        if (usable(p[c])) peak[c] = std::max(peak[c], p[c]);
    }
  for (int c = 0; c < 3; ++c)
    if (usable(v[c]) && v[c] < -kRinging * peak[c]) return true;
  return false;
}

// Luminance integrated over the directions of an image's pixels (negative values as 0).
double imagePower(const Image& image, bool cubeFace) {
  const std::vector<double> texels =
      cubeFace ? faceTexelSolidAngles(image.width) : std::vector<double>();
  double sum = 0.0;
  for (int y = 0; y < image.height; ++y) {
    // Equirect rows: the band between their latitudes, split among the row's pixels.
    const double rowAngle = cubeFace ? 0.0
                                     : 2.0 * std::numbers::pi / image.width *
                                           (std::cos(std::numbers::pi * y / image.height) -
                                            std::cos(std::numbers::pi * (y + 1) / image.height));
    for (int x = 0; x < image.width; ++x) {
      const glm::vec3 v = glm::max(image.at(x, y), glm::vec3(0.0f));
      const double l = usable(v.x) && usable(v.y) && usable(v.z) ? luminance(v) : 0.0;
      sum += l * (cubeFace ? texels[static_cast<std::size_t>(y) * image.width + x] : rowAngle);
    }
  }
  return sum;
}

double environmentPower(const Environment& env) {
  if (!env.isCube()) return imagePower(env.equirect, false);
  double sum = 0.0;
  for (int f = 0; f < kFaceCount; ++f) sum += imagePower(env.cube.face(0, f), true);
  return sum;
}

// Fills the region's pixels from the undamaged ones within 2 pixels of its bounding box.
// (Damaged pixels are written, never read: `image` is both the source and the result.)
void fillRegion(Image& image, const std::vector<std::uint8_t>& mask, const DamagedRegion& r) {
  constexpr int kBorder = 2;
  const int x0 = std::max(r.x0 - kBorder, 0), x1 = std::min(r.x1 + kBorder, image.width - 1);
  const int y0 = std::max(r.y0 - kBorder, 0), y1 = std::min(r.y1 + kBorder, image.height - 1);
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x) {
      if (!mask[static_cast<std::size_t>(y) * image.width + x]) continue;
      glm::dvec3 sum(0.0);
      double weights = 0.0;
      for (int sy = y0; sy <= y1; ++sy)
        for (int sx = x0; sx <= x1; ++sx) {
          const glm::vec3 v = image.at(sx, sy);
          if (mask[static_cast<std::size_t>(sy) * image.width + sx] || !usable(v.x) ||
              !usable(v.y) || !usable(v.z))
            continue;
          const double w = 1.0 / double((sx - x) * (sx - x) + (sy - y) * (sy - y));
          sum += w * glm::dvec3(glm::max(v, glm::vec3(0.0f)));
          weights += w;
        }
      image.at(x, y) = weights > 0.0 ? glm::vec3(sum / weights) : glm::vec3(0.0f);
    }
}

}  // namespace

std::size_t PixelDamage::pixels() const {
  std::size_t n = 0;
  for (const DamagedRegion& r : regions) n += r.pixels;
  return n;
}

std::vector<std::uint8_t> damagedPixelMask(const Image& image) {
  const int w = image.width, h = image.height;
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(w) * h, 0);
  if (image.empty()) return mask;
  const std::vector<glm::vec3> levels = tileLevels(image);
  const float floor = kNoiseFloor * meanLuminance(image);
  const int tilesX = (w + kTile - 1) / kTile;
  const auto level = [&](int x, int y) {
    return levels[static_cast<std::size_t>(y / kTile) * tilesX + x / kTile];
  };
  // Rules 1 and 2.
  parallelFor(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const glm::vec3 m = level(x, y);
      if (contradictsByOrders(image.at(x, y), m) || negativeBeyondNoise(image, x, y, m, floor))
        mask[static_cast<std::size_t>(y) * w + x] = 1;
    }
  });
  // Rule 3: grown a ring at a time from the pixels found so far (rare: serial).
  std::vector<std::pair<int, int>> front;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (mask[static_cast<std::size_t>(y) * w + x]) front.emplace_back(x, y);
  for (int ring = 0; ring < kGrowth && !front.empty(); ++ring) {
    std::vector<std::pair<int, int>> next;
    for (const auto& [x, y] : front)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          std::uint8_t& flag = mask[static_cast<std::size_t>(ny) * w + nx];
          if (flag || !outOfPlace(image.at(nx, ny), level(nx, ny))) continue;
          flag = 1;
          next.emplace_back(nx, ny);
        }
    front = std::move(next);
  }
  return mask;
}

std::vector<DamagedRegion> damagedRegions(std::span<const std::uint8_t> mask, int width, int height,
                                          int face) {
  std::vector<DamagedRegion> regions;
  std::vector<std::uint8_t> seen(mask.begin(), mask.end());
  std::vector<std::pair<int, int>> stack;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (seen[static_cast<std::size_t>(y) * width + x] != 1) continue;
      DamagedRegion r{face, x, y, x, y, 0};
      seen[static_cast<std::size_t>(y) * width + x] = 2;
      stack.emplace_back(x, y);
      while (!stack.empty()) {
        const auto [cx, cy] = stack.back();
        stack.pop_back();
        ++r.pixels;
        r.x0 = std::min(r.x0, cx), r.x1 = std::max(r.x1, cx);
        r.y0 = std::min(r.y0, cy), r.y1 = std::max(r.y1, cy);
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = cx + dx, ny = cy + dy;
            if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
            std::uint8_t& s = seen[static_cast<std::size_t>(ny) * width + nx];
            if (s != 1) continue;
            s = 2;
            stack.emplace_back(nx, ny);
          }
      }
      regions.push_back(r);
    }
  std::stable_sort(
      regions.begin(), regions.end(),
      [](const DamagedRegion& a, const DamagedRegion& b) { return a.pixels > b.pixels; });
  return regions;
}

PixelDamage findPixelDamage(const Environment& env) {
  PixelDamage damage;
  const auto add = [&](const Image& image, int face) {
    const std::vector<DamagedRegion> r =
        damagedRegions(damagedPixelMask(image), image.width, image.height, face);
    damage.regions.insert(damage.regions.end(), r.begin(), r.end());
  };
  if (env.isCube()) {
    if (env.cube.levelCount() > 0)
      for (int f = 0; f < kFaceCount; ++f) add(env.cube.face(0, f), f);
  } else {
    add(env.equirect, 0);
  }
  std::stable_sort(
      damage.regions.begin(), damage.regions.end(),
      [](const DamagedRegion& a, const DamagedRegion& b) { return a.pixels > b.pixels; });
  return damage;
}

DamageRepair repairPixelDamage(Environment& env) {
  DamageRepair repair;
  repair.powerBefore = environmentPower(env);
  const auto repairImage = [&](Image& image, int face) {
    const std::vector<std::uint8_t> mask = damagedPixelMask(image);
    const std::vector<DamagedRegion> regions =
        damagedRegions(mask, image.width, image.height, face);
    for (const DamagedRegion& r : regions) fillRegion(image, mask, r);
    repair.damage.regions.insert(repair.damage.regions.end(), regions.begin(), regions.end());
  };
  if (env.isCube()) {
    if (env.cube.levelCount() > 0) {
      for (int f = 0; f < kFaceCount; ++f) repairImage(env.cube.face(0, f), f);
      if (!repair.damage.empty()) env.cube.levels.resize(1);
    }
  } else {
    repairImage(env.equirect, 0);
  }
  repair.powerAfter = environmentPower(env);
  return repair;
}

}  // namespace ibl
