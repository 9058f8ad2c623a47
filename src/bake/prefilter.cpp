#include "ibl/bake/prefilter.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/core/progress.hpp"
#include "ibl/math/brdf.hpp"
#include "ibl/math/sampling.hpp"
#include "ibl/shared/split_sum.h"

namespace ibl {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// A cube level as flat arrays (directions, radiance, solid angles), face by face and row by
// row: the layout the vectorized convolution loops want.
struct TexelArrays {
  int n = 0;
  std::vector<float> x, y, z, r, g, b, omega;
  explicit TexelArrays(const std::array<Image, kFaceCount>& level) : n(level[0].width) {
    const std::size_t count = static_cast<std::size_t>(kFaceCount) * n * n;
    for (auto* v : {&x, &y, &z, &r, &g, &b, &omega}) v->resize(count);
    const std::vector<double> faceOmega = faceTexelSolidAngles(n);
    std::size_t i = 0;
    for (int f = 0; f < kFaceCount; ++f)
      for (int ty = 0; ty < n; ++ty)
        for (int tx = 0; tx < n; ++tx, ++i) {
          const glm::vec3 d = texelDirection(f, tx, ty, n);
          const glm::vec3 l = level[f].at(tx, ty);
          x[i] = d.x;
          y[i] = d.y;
          z[i] = d.z;
          r[i] = l.x;
          g[i] = l.y;
          b[i] = l.z;
          omega[i] = static_cast<float>(faceOmega[static_cast<std::size_t>(ty) * n + tx]);
        }
  }
  std::size_t size() const { return x.size(); }
  std::size_t rowStart(int face, int row) const {
    return (static_cast<std::size_t>(face) * n + row) * n;
  }
};

// The lobe weight as a function of c = n.l (n = v): proportional to the integrand of the
// prefiltered radiance, zero for c <= 0. With n = v, n.h = v.h = sqrt((1 + c) / 2).
struct LobeWeight {
  enum class Kind { Cosine, Ggx, GgxVisibility, GgxVisibilityFresnel, Charlie } kind;
  float a2 = 0.0f;  // alpha^2

  static LobeWeight forLevel(float roughness, PrefilterWeight w) {
    if (w == PrefilterWeight::Charlie) roughness = std::max(roughness, kMinSheenRoughness);
    const float alpha = alphaFromRoughness(roughness);
    const Kind kind = w == PrefilterWeight::Standard       ? Kind::Ggx
                      : w == PrefilterWeight::FresnelF0One ? Kind::GgxVisibility
                      : w == PrefilterWeight::Charlie      ? Kind::Charlie
                                                           : Kind::GgxVisibilityFresnel;
    return {kind, alpha * alpha};
  }
};

using shared::smoothRise;

// Up to 16 output directions convolved together: the inner loop runs across them, so it
// vectorizes whatever the source texels are (one AVX-512 register, two AVX2 ones).
constexpr int kTileLanes = 16;
struct DestTile {
  alignas(64) float x[kTileLanes], y[kTileLanes], z[kTileLanes];
  alignas(64) float r[kTileLanes], g[kTileLanes], b[kTileLanes], w[kTileLanes];
};

// Adds, for every lane j, the sum over source texels [begin, end) of (L w, w) with
// w = weight(max(n_j . l, 0)) window(n_j . l) omega. kWindow: 0 none, 1 outer edge only,
// 2 both edges (a ring).
// Lambdas of the SIMD loops must be inlined into each target clone, or they run unvectorized.
#define IBL_INLINE __attribute__((always_inline))

template <int kWindow>
[[gnu::always_inline]] inline void accumulateTileBody(const TexelArrays& t, std::size_t begin,
                                                      std::size_t end, DestTile& tile,
                                                      LobeWeight lobe, RadialWindow win) {
  const float a2 = lobe.a2;
  const auto run = [&](auto weight) IBL_INLINE {
    // Local copies: the compiler sees that the sums alias nothing and keeps them in registers
    // (through the tile, whether the loop vectorized depended on inlining decisions).
    alignas(64) float nx[kTileLanes], ny[kTileLanes], nz[kTileLanes];
    alignas(64) float sr[kTileLanes], sg[kTileLanes], sb[kTileLanes], sw[kTileLanes];
    for (int j = 0; j < kTileLanes; ++j) {
      nx[j] = tile.x[j];
      ny[j] = tile.y[j];
      nz[j] = tile.z[j];
      sr[j] = tile.r[j];
      sg[j] = tile.g[j];
      sb[j] = tile.b[j];
      sw[j] = tile.w[j];
    }
    const float* __restrict px = t.x.data() + begin;
    const float* __restrict py = t.y.data() + begin;
    const float* __restrict pz = t.z.data() + begin;
    const float* __restrict pr = t.r.data() + begin;
    const float* __restrict pg = t.g.data() + begin;
    const float* __restrict pb = t.b.data() + begin;
    const float* __restrict po = t.omega.data() + begin;
    const std::size_t count = end - begin;
    for (std::size_t i = 0; i < count; ++i) {
      const float sx = px[i], sy = py[i], sz = pz[i], om = po[i];
      const float lr = pr[i], lg = pg[i], lb = pb[i];
      for (int j = 0; j < kTileLanes; ++j) {
        const float c = std::max(nx[j] * sx + ny[j] * sy + nz[j] * sz, 0.0f);
        float w = weight(c) * om;
        if constexpr (kWindow >= 1) w *= smoothRise(c, win.outerLo, win.outerInv);
        if constexpr (kWindow == 2) w -= weight(c) * om * smoothRise(c, win.innerLo, win.innerInv);
        sr[j] += w * lr;
        sg[j] += w * lg;
        sb[j] += w * lb;
        sw[j] += w;
      }
    }
    for (int j = 0; j < kTileLanes; ++j) {
      tile.r[j] = sr[j];
      tile.g[j] = sg[j];
      tile.b[j] = sb[j];
      tile.w[j] = sw[j];
    }
  };
  // The lobes of ibl/shared/brdf.h (the convolution shader uses the same), one loop each.
  switch (lobe.kind) {
    case LobeWeight::Kind::Cosine:
      run([](float c) IBL_INLINE { return c; });
      break;
    case LobeWeight::Kind::Ggx:
      run([=](float c) IBL_INLINE { return shared::ggxLobe(c, a2); });
      break;
    case LobeWeight::Kind::GgxVisibility:
      run([=](float c) IBL_INLINE { return shared::ggxVisibilityLobe(c, a2); });
      break;
    case LobeWeight::Kind::GgxVisibilityFresnel:
      run([=](float c) IBL_INLINE { return shared::ggxVisibilityFresnelLobe(c, a2); });
      break;
    case LobeWeight::Kind::Charlie: {
      const float exponent = 0.5f / std::sqrt(a2);  // shared::charlieLobe, its root hoisted
      run([=](float c) IBL_INLINE { return c * std::pow(std::max(1.0f - c, 0.0f), exponent); });
      break;
    }
  }
}

// The loops above, compiled for AVX-512, AVX2 and baseline x86-64; the best one runs. (Not
// under ThreadSanitizer: its instrumented ifunc resolvers would run before it starts.)
#if defined(__x86_64__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
#define IBL_SIMD_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define IBL_SIMD_CLONES
#endif
IBL_SIMD_CLONES void accumulateTileAll(const TexelArrays& t, std::size_t begin, std::size_t end,
                                       DestTile& tile, LobeWeight lobe, RadialWindow win) {
  accumulateTileBody<0>(t, begin, end, tile, lobe, win);
}
IBL_SIMD_CLONES void accumulateTileCore(const TexelArrays& t, std::size_t begin, std::size_t end,
                                        DestTile& tile, LobeWeight lobe, RadialWindow win) {
  accumulateTileBody<1>(t, begin, end, tile, lobe, win);
}
IBL_SIMD_CLONES void accumulateTileRing(const TexelArrays& t, std::size_t begin, std::size_t end,
                                        DestTile& tile, LobeWeight lobe, RadialWindow win) {
  accumulateTileBody<2>(t, begin, end, tile, lobe, win);
}

void accumulateTile(const TexelArrays& t, std::size_t begin, std::size_t end, DestTile& tile,
                    LobeWeight lobe, RadialWindow win, bool windowed) {
  if (!windowed)
    accumulateTileAll(t, begin, end, tile, lobe, win);
  else if (win.innerLo > 1.5f)
    accumulateTileCore(t, begin, end, tile, lobe, win);
  else
    accumulateTileRing(t, begin, end, tile, lobe, win);
}

// Accumulates the source texels within angle acos(cosCap) of n (all texels if cosCap <= 0)
// into the tile. Each face row is searched only over the columns the cap can reach: on the
// row at tc, n.d >= k |d| with d = a + sc s + tc t is a quadratic inequality in sc.
void accumulateCap(const TexelArrays& t, glm::vec3 n, float cosCap, DestTile& tile, LobeWeight lobe,
                   RadialWindow win, bool windowed) {
  if (cosCap <= 0.0f) {
    accumulateTile(t, 0, t.size(), tile, lobe, win, windowed);
    return;
  }
  const int size = t.n;
  const float k2 = cosCap * cosCap;
  const float capAngle = std::acos(cosCap);
  for (int f = 0; f < kFaceCount; ++f) {
    const glm::vec3 a = faceAxis(f, 0), s = faceAxis(f, 1), tt = faceAxis(f, 2);
    // Skip faces the cap cannot reach: a face spans at most acos(1/sqrt(3)) from its axis.
    const float na = glm::dot(n, a);
    if (std::acos(std::clamp(na, -1.0f, 1.0f)) > capAngle + 0.9553166f) continue;
    const float B = glm::dot(n, s), nt = glm::dot(n, tt);
    for (int row = 0; row < size; ++row) {
      const float tc = (static_cast<float>(row) + 0.5f) * 2.0f / static_cast<float>(size) - 1.0f;
      const float A = na + tc * nt, Q = 1.0f + tc * tc;
      const float qa = B * B - k2, qb = 2.0f * A * B, qc = A * A - k2 * Q;
      int x0 = 0, x1 = size - 1;
      if (qa < -1e-6f) {
        const float disc = qb * qb - 4.0f * qa * qc;
        if (disc < 0.0f) continue;
        const float root = std::sqrt(disc);
        const float r1 = (-qb + root) / (2.0f * qa), r2 = (-qb - root) / (2.0f * qa);
        const float lo = std::min(r1, r2), hi = std::max(r1, r2);
        if (hi < -1.0f - 1e-3f || lo > 1.0f + 1e-3f) continue;
        const float scale = 0.5f * static_cast<float>(size);
        x0 = std::max(0, static_cast<int>(std::floor((lo + 1.0f) * scale - 0.5f)) - 1);
        x1 = std::min(size - 1, static_cast<int>(std::ceil((hi + 1.0f) * scale - 0.5f)) + 1);
        if (x0 > x1) continue;
      }
      const std::size_t base = t.rowStart(f, row);
      accumulateTile(t, base + x0, base + x1 + 1, tile, lobe, win, windowed);
    }
  }
}

// convolvePass over texel arrays: output texels are processed in square tiles of up to 16
// sharing one cap that covers them all. `progress`, if given, hears of `stage` as tiles finish.
ConvolutionSums convolveTexels(const TexelArrays& texels, int size, LobeWeight lobe,
                               RadialWindow win, float cosCap, const ProgressFn& progress = {},
                               const std::string& stage = {}) {
  const bool windowed = win.outerLo > -2.0f || win.innerLo < 1.5f;
  const int side = std::min(size, 4);  // tile side in texels
  const int tilesPerRow = (size + side - 1) / side;
  ConvolutionSums out;
  for (int f = 0; f < kFaceCount; ++f) {
    out.sum[f] = Image(size, size);
    out.weight[f] = Image(size, size);
  }
  const int tiles = kFaceCount * tilesPerRow * tilesPerRow;
  ProgressCounter counter(progress, stage, tiles);
  parallelFor(0, tiles, [&](int index) {
    const int face = index / (tilesPerRow * tilesPerRow);
    const int ty = index / tilesPerRow % tilesPerRow, tx = index % tilesPerRow;
    const int x0 = tx * side, y0 = ty * side;
    DestTile tile{};
    int lanes = 0;
    for (int y = y0; y < std::min(size, y0 + side); ++y)
      for (int x = x0; x < std::min(size, x0 + side); ++x, ++lanes) {
        const glm::vec3 d = texelDirection(face, x, y, size);
        tile.x[lanes] = d.x;
        tile.y[lanes] = d.y;
        tile.z[lanes] = d.z;
      }
    for (int j = lanes; j < kTileLanes; ++j) {  // unused lanes repeat the first direction
      tile.x[j] = tile.x[0];
      tile.y[j] = tile.y[0];
      tile.z[j] = tile.z[0];
    }
    // One cap for the whole tile: around its center, widened by its angular radius.
    const float inv = 2.0f / static_cast<float>(size);
    const float cx = static_cast<float>(x0) + 0.5f * static_cast<float>(std::min(side, size - x0));
    const float cy = static_cast<float>(y0) + 0.5f * static_cast<float>(std::min(side, size - y0));
    const glm::vec3 center =
        glm::normalize(faceToDirection(face, cx * inv - 1.0f, cy * inv - 1.0f));
    float cap = cosCap;
    if (cosCap > 0.0f) {
      float radius = 0.0f;
      for (int j = 0; j < lanes; ++j)
        radius = std::max(radius, std::acos(std::clamp(
                                      glm::dot(center, glm::vec3(tile.x[j], tile.y[j], tile.z[j])),
                                      -1.0f, 1.0f)));
      const float angle = std::acos(cosCap) + radius + 1e-4f;
      cap = angle >= 0.5f * kPi ? 0.0f : std::cos(angle);
    }
    accumulateCap(texels, center, cap, tile, lobe, win, windowed);
    lanes = 0;
    for (int y = y0; y < std::min(size, y0 + side); ++y)
      for (int x = x0; x < std::min(size, x0 + side); ++x, ++lanes) {
        out.sum[face].at(x, y) = glm::vec3(tile.r[lanes], tile.g[lanes], tile.b[lanes]);
        out.weight[face].at(x, y) = glm::vec3(tile.w[lanes], 0.0f, 0.0f);
      }
    counter.advance();
  });
  return out;
}

std::array<Image, kFaceCount> normalize(const ConvolutionSums& s) {
  std::array<Image, kFaceCount> out;
  for (int f = 0; f < kFaceCount; ++f) {
    out[f] = Image(s.sum[f].width, s.sum[f].height);
    for (std::size_t i = 0; i < out[f].pixels.size(); ++i) {
      const float w = s.weight[f].pixels[i].x;
      out[f].pixels[i] = w > 0.0f ? s.sum[f].pixels[i] / w : glm::vec3(0.0f);
    }
  }
  return out;
}

std::array<Image, kFaceCount> convolveLevel(const std::array<Image, kFaceCount>& sourceLevel,
                                            int size, LobeWeight lobe,
                                            const ProgressFn& progress = {},
                                            const std::string& stage = {}) {
  return normalize(
      convolveTexels(TexelArrays(sourceLevel), size, lobe, RadialWindow{}, 0.0f, progress, stage));
}

std::vector<glm::vec3> convolveDirections(const std::array<Image, kFaceCount>& sourceLevel,
                                          std::span<const glm::vec3> dirs, LobeWeight lobe) {
  const TexelArrays texels(sourceLevel);
  std::vector<glm::vec3> out(dirs.size());
  const std::size_t tiles = (dirs.size() + kTileLanes - 1) / kTileLanes;
  parallelFor(std::size_t{0}, tiles, [&](std::size_t t) {
    DestTile tile{};
    const std::size_t first = t * kTileLanes;
    for (int j = 0; j < kTileLanes; ++j) {
      const glm::vec3 d = glm::normalize(dirs[std::min(first + j, dirs.size() - 1)]);
      tile.x[j] = d.x;
      tile.y[j] = d.y;
      tile.z[j] = d.z;
    }
    accumulateTile(texels, 0, texels.size(), tile, lobe, RadialWindow{}, false);
    for (std::size_t j = 0; j < kTileLanes && first + j < dirs.size(); ++j)
      out[first + j] = tile.w[j] > 0.0f ? glm::vec3(tile.r[j], tile.g[j], tile.b[j]) / tile.w[j]
                                        : glm::vec3(0.0f);
  });
  return out;
}

// Finest level of `cube` whose texels (about 2 / n radians) are no wider than `angle`, and
// no finer than needed.
int levelForTexelAngle(const CubeMap& cube, float angle) {
  int level = cube.levelCount() - 1;
  while (level > 0 && 2.0f / static_cast<float>(cube.levels[level][0].width) > angle) --level;
  return level;
}

// Source resolution, in texels per lobe half width: the lobe's core (sharp lobes) and whole
// lobes (wide ones, where a single pass over the sphere is cheap). Tuned with ibl_accuracy.
constexpr float kCoreTexelsPerLobe = 3.0f;
// The coarsest level a lobe's core reads: on 32^2 (texels of 0.06 rad against the core's
// radial windows) park's r = 0.43 level of a 1024^2 chain was 0.9 % off, on 64^2 0.19 %.
constexpr int kCoreMinSourceSize = 64;
constexpr float kDirectTexelsPerLobe = 12.0f;

// Angle from the lobe axis at which the lobe falls to half its peak (n = v): n.h at half
// maximum of D satisfies sin(theta_h) ~ 0.64 alpha, and theta_l = 2 theta_h.
float lobeHalfWidth(float alpha) {
  return 2.0f * std::asin(std::min(1.0f, 0.64f * alpha));
}

}  // namespace

ConvolutionSums convolvePass(const std::array<Image, kFaceCount>& sourceLevel, int size,
                             float roughness, PrefilterWeight weight, RadialWindow window,
                             float cosCap) {
  return convolveTexels(TexelArrays(sourceLevel), size, LobeWeight::forLevel(roughness, weight),
                        window, cosCap);
}

namespace {

// Broad lobes, computed in one direct pass over the sphere at no more than `maxSize`^2 and
// interpolated up, reading the level with texels of `texelAngle`:
// - the F0 = 0 lobe of the Fresnel-weighted variant, (1 - v.h)^5 D V (n.l), vanishes on its
//   axis and grows toward grazing angles whatever the roughness: not a core with tails (no
//   rings), but a broad function of n.l that varies on scales of 0.35 rad or more; texels an
//   eighth of that, 32^2. Measured against brute-force quadrature: 5e-6.
// - the Charlie lobe (1 - c)^(1 / (2 alpha)) c peaks at c = 1 / (1 + 1 / (2 alpha)), near the
//   horizon for smooth sheen, over a width of about that much in c; the prefiltered radiance
//   averages a whole ring around n, smooth on the scale of 16^2 texels.
std::array<Image, kFaceCount> prefilterLevelBroad(const CubeMap& source, int size, float roughness,
                                                  PrefilterWeight weight, LevelMethod* info,
                                                  const ConvolutionPassFn& pass) {
  float texelAngle = 0.35f / 8.0f;
  int maxSize = 32;
  if (weight == PrefilterWeight::Charlie) {
    const float alpha = alphaFromRoughness(std::max(roughness, kMinSheenRoughness));
    const float peak = 1.0f / (1.0f + 0.5f / alpha);  // in c, about the lobe's width too
    texelAngle = std::max(peak / 2.0f, 2.0f / 64.0f);
    maxSize = 16;
  }
  const int level = levelForTexelAngle(source, texelAngle);
  const int coarse = std::min(size, maxSize);
  if (info) {
    info->method = "direct";
    info->sourceSize = source.levels[level][0].width;
    info->computedSize = coarse;
  }
  std::array<Image, kFaceCount> result =
      normalize(pass(source.levels[level], coarse, roughness, weight, RadialWindow{}, 0.0f));
  if (coarse == size) return result;
  CubeMap cube;
  cube.levels = {std::move(result)};
  std::array<Image, kFaceCount> out;
  for (auto& face : out) face = Image(size, size);
  parallelFor(0, kFaceCount * size, [&](int row) {
    const int face = row / size, y = row % size;
    for (int x = 0; x < size; ++x)
      out[face].at(x, y) = sampleBilinear(cube, 0, texelDirection(face, x, y, size));
  });
  return out;
}

// Output texels per lobe half width beyond which a level is computed coarser and interpolated
// up: the prefiltered radiance varies on the lobe's scale, and 8 texels per half width
// resolve it (the default chain has 3 to 8). Without this, a chain of few levels or a large
// size pays for output texels far finer than its lobes (--levels 3: 20 and 44 per half width).
constexpr float kOutputTexelsPerLobe = 8.0f;

// The size a level of `size` is computed at: halved while the half still has
// kOutputTexelsPerLobe texels (2 / n radians wide) per lobe half width theta.
int workingSize(int size, float theta) {
  int n = size;
  while (n > kMinSpecularSize && theta * static_cast<float>(n / 2) / 2.0f >= kOutputTexelsPerLobe)
    n /= 2;
  return n;
}

// A prefiltered level computed at a coarser size, interpolated up to `size` with Catmull-Rom
// splines (sharper than bilinear on the lobe's scale; negative overshoot clamped to 0).
std::array<Image, kFaceCount> interpolateLevel(const std::array<Image, kFaceCount>& coarse,
                                               int size) {
  CubeMap cube;
  cube.levels = {coarse};
  std::array<Image, kFaceCount> out;
  for (auto& face : out) face = Image(size, size);
  parallelFor(0, kFaceCount * size, [&](int row) {
    const int face = row / size, y = row % size;
    for (int x = 0; x < size; ++x)
      out[face].at(x, y) =
          glm::max(sampleCubic(cube, 0, texelDirection(face, x, y, size)), glm::vec3(0.0f));
  });
  return out;
}

}  // namespace

std::array<Image, kFaceCount> prefilterLevelRings(const CubeMap& source, int size, float roughness,
                                                  PrefilterWeight weight, LevelMethod* info,
                                                  const ConvolutionPassFn& passFn) {
  const ConvolutionPassFn& pass = passFn ? passFn : ConvolutionPassFn(convolvePass);
  const float theta = lobeHalfWidth(alphaFromRoughness(roughness));
  constexpr float kPiF = std::numbers::pi_v<float>;
  // Ring 0, the lobe's core: texels at most a third of its half width, cap 2 b1.
  const float b1 = 2.0f * theta;
  if (weight == PrefilterWeight::FresnelF0Zero || weight == PrefilterWeight::Charlie)
    return prefilterLevelBroad(source, size, roughness, weight, info, pass);
  if (const int work = workingSize(size, theta); work < size) {
    std::array<Image, kFaceCount> coarse =
        prefilterLevelRings(source, work, roughness, weight, info, pass);
    if (info) info->computedSize = work;
    return interpolateLevel(coarse, size);
  }
  if (2.0f * b1 >= 0.5f * kPiF) {
    // A wide lobe: one pass over the whole sphere, with texels a twelfth of its half width.
    const int level = levelForTexelAngle(source, theta / kDirectTexelsPerLobe);
    if (info) {
      info->method = "direct";
      info->sourceSize = source.levels[level][0].width;
    }
    return normalize(pass(source.levels[level], size, roughness, weight, RadialWindow{}, 0.0f));
  }
  // The core reads texels a third of the lobe's half width (finer costs 16 pi (theta/texel)^2
  // texels per output texel and gains nothing measurable), and no coarser than 64^2 nor the
  // output.
  const int core = std::min(levelForTexelAngle(source, theta / kCoreTexelsPerLobe),
                            levelOfSize(source, std::min(size, kCoreMinSourceSize)));
  if (info) info->sourceSize = source.levels[core][0].width;

  const auto rise = [](float thetaOne, float thetaZero) {  // 1 inside thetaOne, 0 beyond thetaZero
    const float lo = std::cos(thetaZero), hi = std::cos(thetaOne);
    return std::pair{lo, 1.0f / (hi - lo)};
  };
  RadialWindow w0;
  std::tie(w0.outerLo, w0.outerInv) = rise(b1, 2.0f * b1);
  ConvolutionSums total =
      pass(source.levels[core], size, roughness, weight, w0, std::cos(2.0f * b1));
  if (info) info->method = "rings";
  // Ring k covers [b_k, 4 b_k], where the lobe is smooth on the scale of b_k: it reads, and is
  // computed at, a level with texels of b_k / 3, then is interpolated up and added.
  for (float bk = b1;; bk *= 2.0f) {
    const bool last = 4.0f * bk >= kPiF;
    RadialWindow win;
    if (!last) std::tie(win.outerLo, win.outerInv) = rise(2.0f * bk, 4.0f * bk);
    std::tie(win.innerLo, win.innerInv) = rise(bk, 2.0f * bk);
    const int level = levelForTexelAngle(source, bk / 3.0f);
    const int ringSize = std::min(size, source.levels[level][0].width);
    const ConvolutionSums ring = pass(source.levels[level], ringSize, roughness, weight, win,
                                      last ? 0.0f : std::cos(4.0f * bk));
    if (ringSize == size) {
      for (int f = 0; f < kFaceCount; ++f)
        for (std::size_t i = 0; i < total.sum[f].pixels.size(); ++i) {
          total.sum[f].pixels[i] += ring.sum[f].pixels[i];
          total.weight[f].pixels[i] += ring.weight[f].pixels[i];
        }
    } else {
      CubeMap sums, weights;
      sums.levels = {ring.sum};
      weights.levels = {ring.weight};
      parallelFor(0, kFaceCount * size, [&](int row) {
        const int face = row / size, y = row % size;
        for (int x = 0; x < size; ++x) {
          const glm::vec3 d = texelDirection(face, x, y, size);
          total.sum[face].at(x, y) += sampleBilinear(sums, 0, d);
          total.weight[face].at(x, y) += sampleBilinear(weights, 0, d);
        }
      });
    }
    if (last) break;
  }
  return normalize(total);
}

std::vector<glm::vec3> prefilterDirections(const std::array<Image, kFaceCount>& sourceLevel,
                                           std::span<const glm::vec3> dirs, float roughness,
                                           PrefilterWeight weight) {
  return convolveDirections(sourceLevel, dirs, LobeWeight::forLevel(roughness, weight));
}

std::vector<glm::vec3> irradianceDirections(const std::array<Image, kFaceCount>& sourceLevel,
                                            std::span<const glm::vec3> dirs) {
  return convolveDirections(sourceLevel, dirs, {LobeWeight::Kind::Cosine, 0.0f});
}

std::string_view mappingName(RoughnessMapping mapping) {
  switch (mapping) {
    case RoughnessMapping::Linear:
      return "linear";
    case RoughnessMapping::Frostbite:
      return "frostbite";
    case RoughnessMapping::Filament:
      return "filament";
    case RoughnessMapping::Babylon:
      return "babylon";
  }
  return "?";
}

float roughnessForLevel(int level, int levelCount, RoughnessMapping mapping) {
  if (levelCount <= 1) return 0.0f;
  const float t = static_cast<float>(level) / static_cast<float>(levelCount - 1);
  switch (mapping) {
    case RoughnessMapping::Linear:
      return t;
    case RoughnessMapping::Frostbite:
      return t * t;
    case RoughnessMapping::Filament:  // the root of lod / (L - 1) = r (2 - r) in [0, 1]
      return std::clamp(1.0f - std::sqrt(std::max(1.0f - t, 0.0f)), 0.0f, 1.0f);
    case RoughnessMapping::Babylon: {  // alpha = 2^(m / 0.8) / 2^(L - 1)
      if (level == 0) return 0.0f;
      const float alpha = std::exp2(static_cast<float>(level) / kBabylonLodGenerationScale -
                                    static_cast<float>(levelCount - 1));
      return std::sqrt(std::min(alpha, 1.0f));
    }
  }
  return t;
}

float specularLodForRoughness(float roughness, int levelCount, RoughnessMapping mapping) {
  const float maxLod = static_cast<float>(std::max(levelCount - 1, 0));
  if (mapping == RoughnessMapping::Filament) return maxLod * roughness * (2.0f - roughness);
  if (mapping == RoughnessMapping::Babylon) {  // 0.8 log2(width r^2), width = 2^maxLod
    if (roughness <= 0.0f) return 0.0f;
    const float lod = kBabylonLodGenerationScale * (maxLod + 2.0f * std::log2(roughness));
    return std::clamp(lod, 0.0f, maxLod);
  }
  return shared::specularLodForRoughness(roughness, maxLod, mapping == RoughnessMapping::Frostbite);
}

int defaultSpecularLevels(int size) {
  int levels = 1;
  while ((size >> levels) >= kMinSpecularSize) ++levels;
  return levels;
}

int specularLevelCount(const PrefilterOptions& o) {
  return o.levels > 0 ? std::min(o.levels, fullMipCount(o.size)) : defaultSpecularLevels(o.size);
}

int levelOfSize(const CubeMap& cube, int size) {
  for (int m = 0; m < cube.levelCount(); ++m)
    if (cube.levels[m][0].width <= size) return m;
  return cube.levelCount() - 1;
}

std::array<Image, kFaceCount> prefilterLevelDirect(const CubeMap& source, int sourceLevel, int size,
                                                   float roughness, PrefilterWeight weight) {
  return convolveLevel(source.levels[sourceLevel], size, LobeWeight::forLevel(roughness, weight));
}

std::vector<FisSample> filteredImportanceSamples(int sourceSize, int sourceLevels, float roughness,
                                                 int samples, PrefilterWeight weight) {
  const float alpha = alphaFromRoughness(roughness);
  const int n0 = sourceSize;
  const float texelSolidAngle0 =
      4.0f * kPi / (6.0f * static_cast<float>(n0) * static_cast<float>(n0));
  const float maxLod = static_cast<float>(sourceLevels - 1);
  // One set of samples in the tangent frame, shared by every texel: no noise.
  std::vector<FisSample> set;
  for (int k = 0; k < samples; ++k) {
    const glm::vec3 h = sampleGgxHalfVector(
        hammersley(static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(samples)), alpha);
    const glm::vec3 l(2.0f * h.z * h.x, 2.0f * h.z * h.y, 2.0f * h.z * h.z - 1.0f);
    const float c = l.z;
    if (c <= 0.0f) continue;
    // pdf of l = D(h) (n.h) / (4 v.h) = D / 4 with n = v; the sample stands for 1 / (N pdf).
    const float pdf = ggxDistribution(h.z, alpha) * 0.25f;
    const float sampleSolidAngle = 1.0f / (static_cast<float>(samples) * pdf);
    const float lod =
        std::clamp(0.5f * std::log2(sampleSolidAngle / texelSolidAngle0) + 1.0f, 0.0f, maxLod);
    float w = c;  // Karis: the n.l weight; D cancels with the pdf
    if (weight != PrefilterWeight::Standard) {
      w *= smithGgxCorrelatedVisibility(1.0f, c, alpha);
      if (weight == PrefilterWeight::FresnelF0Zero) w *= schlickWeight(h.z);
    }
    set.push_back({l, lod, w});
  }
  return set;
}

std::array<Image, kFaceCount> prefilterLevelSampled(const CubeMap& source, int size,
                                                    float roughness, int samples,
                                                    PrefilterWeight weight) {
  const std::vector<FisSample> set =
      filteredImportanceSamples(source.size(), source.levelCount(), roughness, samples, weight);
  std::array<Image, kFaceCount> out;
  for (auto& f : out) f = Image(size, size);
  parallelFor(0, kFaceCount * size, [&](int row) {
    const int face = row / size, y = row % size;
    for (int x = 0; x < size; ++x) {
      const glm::mat3 frame = tangentFrame(texelDirection(face, x, y, size));
      glm::vec3 sum(0.0f);
      float wsum = 0.0f;
      for (const FisSample& s : set) {
        sum += sampleTrilinear(source, s.lod, frame * s.l) * s.weight;
        wsum += s.weight;
      }
      out[face].at(x, y) = wsum > 0.0f ? sum / wsum : glm::vec3(0.0f);
    }
  });
  return out;
}

CubeMap buildSpecularChain(const CubeMap& source, const PrefilterOptions& o,
                           const SpecularLevelFn& level, std::vector<LevelMethod>* methods,
                           const ProgressFn& progress) {
  if (!std::has_single_bit(static_cast<unsigned>(o.size)))
    fail("prefilter", fmt::format("specular size must be a power of two, not {}", o.size));
  if (source.levelCount() != fullMipCount(source.size()))
    fail("prefilter", "the source cube map needs its full mip chain");
  const int levels = specularLevelCount(o);
  CubeMap out;
  out.levels.resize(levels);
  if (methods) methods->assign(levels, {});
  for (int m = 0; m < levels; ++m) {
    const int size = o.size >> m;
    const float r = roughnessForLevel(m, levels, o.mapping);
    const std::string stage =
        fmt::format("specular level {}/{} ({}x{}, roughness {:.3f})", m + 1, levels, size, size, r);
    if (progress) progress(stage, 0.0);
    LevelMethod method{r, "", 0, 0, size};
    if (r == 0.0f && o.weight != PrefilterWeight::Charlie) {
      // Mirror reflection: the source itself (the sheen lobe has no mirror limit).
      const int sl = levelOfSize(source, size);
      method.method = "source";
      method.sourceSize = source.levels[sl][0].width;
      out.levels[m] = source.levels[sl];
    } else {
      out.levels[m] = level(size, r, method);
    }
    if (methods) (*methods)[m] = method;
    if (progress) progress(stage, 1.0);
  }
  return out;
}

CubeMap prefilterGgx(const CubeMap& source, const PrefilterOptions& o,
                     std::vector<LevelMethod>* methods, const ProgressFn& progress) {
  const auto level = [&](int size, float r, LevelMethod& method) {
    if (o.method == PrefilterMethod::Sampled) {
      method.method = "sampled";
      method.sourceSize = source.size();
      method.samples = o.samples;
      return prefilterLevelSampled(source, size, r, o.samples, o.weight);
    }
    return prefilterLevelRings(source, size, r, o.weight, &method);
  };
  return buildSpecularChain(source, o, level, methods, progress);
}

CubeMap convolveIrradiance(const CubeMap& source, int size, int sourceLevel,
                           const ProgressFn& progress) {
  const std::string stage = fmt::format("irradiance {}x{}", size, size);
  if (progress) progress(stage, 0.0);
  CubeMap out;
  out.levels.push_back(convolveLevel(source.levels[sourceLevel], size,
                                     {LobeWeight::Kind::Cosine, 0.0f}, progress, stage));
  return out;
}

}  // namespace ibl
