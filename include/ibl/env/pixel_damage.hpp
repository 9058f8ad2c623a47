#pragma once
// API: stable
// Damaged pixels of an HDR image: blocks that lossy compression (OpenEXR's DWAA/DWAB, JPEG-XR)
// or a broken conversion destroyed, found by how they contradict their neighbourhood, and their
// repair from that neighbourhood.
//
// The rule (docs/cli.md#damaged-pixels). Each pixel is compared with its neighbourhood's level
// m, per channel: the median of the pixels at even offsets within the 24 x 24 pixels of the
// 3 x 3 tiles of 8 x 8 pixels around the pixel's own tile (144 samples, clamped at the image's
// edges; one tile's damage is a ninth of them, too few to carry the median beyond the undamaged
// samples' range). A pixel is
// damaged when
//   1. one of its channels is at least 100 times the neighbourhood's (v_i >= 100 m_i, m_i > 0)
//   while
//      another is at most a hundredth of it (v_j <= m_j / 100, m_j > 0; zero and negative
//      values count): its channels contradict each other and the neighbourhood by orders of
//      magnitude, which no light source does (a sun raises every channel over the sky it
//      stands in); or
//   2. one of its channels is negative beyond the file's noise: v_c < -0.5 max(P_c, m_c, f), where
//      P_c is the largest value of that channel in the 5 x 5 pixels around it (lossy codecs ring
//      below zero beside a bright source by a fraction of its peak: under a quarter for
//      DCT blocks) and f = 10^-3 times the image's mean luminance (the noise of black areas); or
//   3. it touches (8-connected) a damaged pixel and one of its channels is an order of magnitude
//      below the neighbourhood's or two above it (v_c <= m_c / 10 or v_c >= 100 m_c, m_c > 0):
//      the rest of a destroyed block (the glow of a real source beside it, up to 100 times its
//      surroundings in every channel, stays); grown at most 8 pixels from rules 1 and 2.
// Pixels that are NaN or infinite are left to sanitizePixels (they are counted there).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "ibl/core/image.hpp"

namespace ibl {

struct Environment;  // environment.hpp

// One 8-connected group of damaged pixels.
struct DamagedRegion {
  int face = 0;        // 0 for a flat image; the cube face (0..5: +X -X +Y -Y +Z -Z)
  int x0 = 0, y0 = 0;  // bounding box, pixels, inclusive
  int x1 = 0, y1 = 0;  //
  std::size_t pixels = 0;
};

struct PixelDamage {
  std::vector<DamagedRegion> regions;  // largest first
  std::size_t pixels() const;          // over all regions
  bool empty() const { return regions.empty(); }
};

// The damaged pixels of one image by the rule above: 1 where damaged, row-major, width x height.
std::vector<std::uint8_t> damagedPixelMask(const Image& image);

// The 8-connected regions of a mask (damagedPixelMask's), largest first; `face` is copied into
// each.
std::vector<DamagedRegion> damagedRegions(std::span<const std::uint8_t> mask, int width, int height,
                                          int face);

// The damage of every image of an environment (the equirect, or level 0 of each cube face).
PixelDamage findPixelDamage(const Environment& env);

// How a repair changed an environment.
struct DamageRepair {
  PixelDamage damage;           // what was repaired
  double powerBefore = 0;       // luminance integrated over the sphere (relative units x sr)
  double powerAfter = 0;        //
  double powerChange() const {  // relative: (after - before) / before; 0 when before is 0
    return powerBefore > 0 ? (powerAfter - powerBefore) / powerBefore : 0.0;
  }
};

// Replaces every damaged pixel (of level 0; a cube's other levels are dropped, to be made again
// from the repaired one) by the inverse-square-distance weighted mean of the undamaged pixels
// within 2 pixels of its region's bounding box, and measures the change of the environment's
// power, its negative values counted as 0 (as they are read). Does nothing where nothing is
// damaged.
DamageRepair repairPixelDamage(Environment& env);

}  // namespace ibl
