// Accuracy report of the default bake, for the bundled HDRIs (sunset has a visible sun):
//  - each prefiltered specular level and the irradiance cube against brute-force references
//    (direct quadrature over every texel of the 256^2 source), as relative RMSE of luminance
//    over texels (all texels, or 3000 fixed random ones on large levels), for the default
//    direct method and for filtered importance sampling (64 samples);
//  - the C(n, l)-weighted prefilter (F0 = 1) against the standard one;
//  - SH9 irradiance, plain and windowed, against the exact irradiance cube;
//  - the analytic DFG fits against the 128^2 table.
//   ibl_accuracy [hdri ...]     (default: sunset park studio)
//   ibl_accuracy --chain SIZE[,LEVELS] [hdri ...]   one chain of other options, level by level
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "ibl/bake/dfg.hpp"
#include "ibl/bake/prefilter.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/math/brdf.hpp"
#include "ibl/math/color.hpp"
#include "ibl/math/sh.hpp"
#include "ibl/shared/brdf.h"

namespace {

using Clock = std::chrono::steady_clock;

struct TexelRef {
  int face;
  int x, y;
};

// All texels of a level, or a fixed random subset of `limit`.
std::vector<TexelRef> pickTexels(int size, std::size_t limit) {
  std::vector<TexelRef> all;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) all.push_back({f, x, y});
  if (all.size() <= limit) return all;
  std::mt19937 rng(12345);
  std::shuffle(all.begin(), all.end(), rng);
  all.resize(limit);
  return all;
}

double relativeRmse(const std::vector<float>& a, const std::vector<float>& ref) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    num += (double(a[i]) - ref[i]) * (double(a[i]) - ref[i]);
    den += double(ref[i]) * ref[i];
  }
  return std::sqrt(num / den);
}

// Relative RMSE of luminance of `level` against a brute-force reference over `source`.
double levelError(const std::array<ibl::Image, 6>& level, const std::array<ibl::Image, 6>& source,
                  float roughness, bool irradiance) {
  const int size = level[0].width;
  const auto texels = pickTexels(size, 3000);
  std::vector<glm::vec3> dirs;
  for (const auto& t : texels) dirs.push_back(ibl::texelDirection(t.face, t.x, t.y, size));
  const auto ref = irradiance ? ibl::irradianceDirections(source, dirs)
                              : ibl::prefilterDirections(source, dirs, roughness,
                                                         ibl::PrefilterWeight::Standard);
  std::vector<float> a, b;
  for (std::size_t i = 0; i < texels.size(); ++i) {
    a.push_back(ibl::luminance(level[texels[i].face].at(texels[i].x, texels[i].y)));
    b.push_back(ibl::luminance(ref[i]));
  }
  return relativeRmse(a, b);
}

double imageDifference(const std::array<ibl::Image, 6>& a, const std::array<ibl::Image, 6>& ref) {
  std::vector<float> x, y;
  for (int f = 0; f < 6; ++f)
    for (std::size_t i = 0; i < a[f].pixels.size(); ++i) {
      x.push_back(ibl::luminance(a[f].pixels[i]));
      y.push_back(ibl::luminance(ref[f].pixels[i]));
    }
  return relativeRmse(x, y);
}

double ms(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void reportEnvironment(const std::string& name) {
  const auto env =
      ibl::loadEnvironment(std::string(IBL_BENCH_DATA) + "/hdri/" + name + ".exr").environment;
  ibl::CubeMap source = ibl::resampleToCube(env, 256);
  ibl::buildMipChain(source);
  fmt::print(
      "{}: relative RMSE of luminance against brute-force quadrature over the 256^2 source\n",
      name);
  ibl::CubeMap standard;
  for (auto method : {ibl::PrefilterMethod::Direct, ibl::PrefilterMethod::Sampled}) {
    ibl::PrefilterOptions options;
    options.method = method;
    std::vector<ibl::LevelMethod> levels;
    const auto t0 = Clock::now();
    ibl::CubeMap specular = ibl::prefilterGgx(source, options, &levels);
    const double t = ms(t0);
    fmt::print("  specular, {} ({:.0f} ms)\n",
               method == ibl::PrefilterMethod::Direct ? "direct quadrature (default)"
                                                      : "filtered importance sampling, 64 samples",
               t);
    for (int m = 1; m < specular.levelCount(); ++m)
      fmt::print(
          "    level {}  {:3}^2  r = {:.1f}  {:7} source {:3}^2  {:7.3f} %\n", m,
          specular.levels[m][0].width, levels[m].roughness, levels[m].method, levels[m].sourceSize,
          100.0 * levelError(specular.levels[m], source.levels[0], levels[m].roughness, false));
    if (method == ibl::PrefilterMethod::Direct) standard = std::move(specular);
  }
  const auto t1 = Clock::now();
  const ibl::CubeMap irradiance = ibl::convolveIrradiance(source, 32, ibl::levelOfSize(source, 32));
  const double tIrr = ms(t1);
  fmt::print("  irradiance 32^2, direct over the 32^2 level ({:.0f} ms)     {:7.3f} %\n", tIrr,
             100.0 * levelError(irradiance.levels[0], source.levels[0], 0.0f, true));

  ibl::PrefilterOptions variant;
  variant.weight = ibl::PrefilterWeight::FresnelF0One;
  const ibl::CubeMap fresnel = ibl::prefilterGgx(source, variant);
  fmt::print("  C(n,l)-weighted prefilter (F0 = 1) vs standard, per level:");
  for (int m = 1; m < fresnel.levelCount(); ++m)
    fmt::print(" {:.2f} %", 100.0 * imageDifference(fresnel.levels[m], standard.levels[m]));
  fmt::print("\n");

  const ibl::Sh9 sh = ibl::projectSh9(source, 0);
  for (const ibl::ShWindow window :
       {ibl::ShWindow::Off, ibl::ShWindow::Lanczos, ibl::ShWindow::Cmgen}) {
    std::array<float, 3> factors{};
    const ibl::Sh9 coefficients = ibl::windowSh9(sh, window, &factors);
    std::array<ibl::Image, 6> fromSh;
    float lowest = 1e30f;  // the smallest channel of the SH irradiance over the cube's texels
    for (int f = 0; f < 6; ++f) {
      fromSh[f] = ibl::Image(32, 32);
      for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
          const glm::vec3 e = ibl::irradianceSh9(coefficients, ibl::texelDirection(f, x, y, 32)) /
                              std::numbers::pi_v<float>;
          fromSh[f].at(x, y) = e;
          lowest = std::min({lowest, e.x, e.y, e.z});
        }
    }
    const char* label = window == ibl::ShWindow::Off       ? "exact  "
                        : window == ibl::ShWindow::Lanczos ? "lanczos"
                                                           : "cmgen  ";
    fmt::print(
        "  SH9 irradiance, window {} ({:.3f}, {:.3f}) vs exact cube {:7.3f} %, lowest {:+.4f}\n",
        label, factors[1], factors[2], 100.0 * imageDifference(fromSh, irradiance.levels[0]),
        lowest);
  }
}

// Brute-force prefiltered radiance (luminance) in `dirs` over every texel of `level`, summed
// row by row in float and across rows in double: over the 6.3 M texels of a 1024^2 cube a
// float sum alone drifts by ~0.3 %, more than the errors measured.
std::vector<double> referenceLuminance(const std::array<ibl::Image, 6>& level,
                                       const std::vector<glm::vec3>& dirs, float roughness) {
  const int n = level[0].width;
  const std::vector<double> faceOmega = ibl::faceTexelSolidAngles(n);
  const std::size_t count = static_cast<std::size_t>(6) * n * n;
  std::vector<float> x(count), y(count), z(count), om(count), lum(count);
  for (int f = 0; f < 6; ++f)
    for (int ty = 0; ty < n; ++ty)
      for (int tx = 0; tx < n; ++tx) {
        const std::size_t i = (static_cast<std::size_t>(f) * n + ty) * n + tx;
        const glm::vec3 d = ibl::texelDirection(f, tx, ty, n);
        x[i] = d.x;
        y[i] = d.y;
        z[i] = d.z;
        om[i] = static_cast<float>(faceOmega[static_cast<std::size_t>(ty) * n + tx]);
        lum[i] = ibl::luminance(level[f].at(tx, ty));
      }
  const float alpha = ibl::alphaFromRoughness(roughness), a2 = alpha * alpha;
  std::vector<double> out(dirs.size());
  ibl::parallelFor(std::size_t{0}, dirs.size(), [&](std::size_t k) {
    const glm::vec3 d = glm::normalize(dirs[k]);
    double sum = 0.0, wsum = 0.0;
    for (std::size_t row = 0; row < static_cast<std::size_t>(6) * n; ++row) {
      float s = 0.0f, w = 0.0f;
      for (std::size_t i = row * n; i < (row + 1) * n; ++i) {
        const float c = std::max(d.x * x[i] + d.y * y[i] + d.z * z[i], 0.0f);
        const float wi = ibl::shared::ggxLobe(c, a2) * om[i];
        s += wi * lum[i];
        w += wi;
      }
      sum += s;
      wsum += w;
    }
    out[k] = wsum > 0.0 ? sum / wsum : 0.0;
  });
  return out;
}

// One specular chain of `size` and `levels` (0: default) against brute-force quadrature over
// its own source level 0 (at most `limit` texels per level): what the options users pick cost
// and how close they are.
void reportChain(const std::string& name, int size, int levels, std::size_t limit) {
  const auto env =
      ibl::loadEnvironment(std::string(IBL_BENCH_DATA) + "/hdri/" + name + ".exr").environment;
  ibl::CubeMap source = ibl::resampleToCube(env, size);
  ibl::buildMipChain(source);
  ibl::PrefilterOptions options;
  options.size = size;
  options.levels = levels;
  std::vector<ibl::LevelMethod> methods;
  const auto t0 = Clock::now();
  const ibl::CubeMap specular = ibl::prefilterGgx(source, options, &methods);
  fmt::print(
      "{}: chain {}^2, {} levels ({:.0f} ms), relative RMSE against quadrature over the "
      "{}^2 source\n",
      name, size, specular.levelCount(), ms(t0), size);
  for (int m = 1; m < specular.levelCount(); ++m) {
    const auto& level = specular.levels[m];
    const int n = level[0].width;
    const auto texels = pickTexels(n, limit);
    std::vector<glm::vec3> dirs;
    for (const auto& t : texels) dirs.push_back(ibl::texelDirection(t.face, t.x, t.y, n));
    const std::vector<double> ref =
        referenceLuminance(source.levels[0], dirs, methods[m].roughness);
    std::vector<float> a, b;
    for (std::size_t i = 0; i < texels.size(); ++i) {
      a.push_back(ibl::luminance(level[texels[i].face].at(texels[i].x, texels[i].y)));
      b.push_back(static_cast<float>(ref[i]));
    }
    fmt::print(
        "  level {}  {:4}^2  r = {:.3f}  {:7} source {:4}^2  computed at {:4}^2  {:7.3f} %\n", m, n,
        methods[m].roughness, methods[m].method, methods[m].sourceSize, methods[m].computedSize,
        100.0 * relativeRmse(a, b));
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> names;
  int chainSize = 0, chainLevels = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--chain" && i + 1 < argc) {
      // --chain SIZE[,LEVELS]
      const std::string v = argv[++i];
      chainSize = std::stoi(v);
      if (const auto comma = v.find(','); comma != std::string::npos)
        chainLevels = std::stoi(v.substr(comma + 1));
    } else {
      names.push_back(arg);
    }
  }
  if (names.empty()) names = {"sunset", "park", "studio"};
  if (chainSize > 0) {
    for (const auto& name : names)
      reportChain(name, chainSize, chainLevels, chainSize > 256 ? 400 : 3000);
    return 0;
  }
  for (const auto& name : names) reportEnvironment(name);

  // Analytic DFG fits against the table (A, B).
  const ibl::Image lut = ibl::integrateDfgLut(128, 128, 512);
  for (auto [label, fit] : {std::pair{"UE4 mobile (Karis 2014)", &ibl::dfgUe4Mobile},
                            std::pair{"Black Ops II (Lazarov 2013)", &ibl::dfgBlackOps2}}) {
    double sq = 0.0, worst = 0.0;
    for (int j = 0; j < 128; ++j)
      for (int i = 0; i < 128; ++i) {
        const glm::vec2 ref(lut.at(i, j).x, lut.at(i, j).y);
        const glm::vec2 v = fit((j + 0.5f) / 128.0f, (i + 0.5f) / 128.0f);
        for (int c = 0; c < 2; ++c) {
          sq += (v[c] - ref[c]) * (v[c] - ref[c]);
          worst = std::max(worst, double(std::abs(v[c] - ref[c])));
        }
      }
    fmt::print("DFG fit {}: RMS error {:.4f}, max {:.4f} (A and B, over the 128^2 table)\n", label,
               std::sqrt(sq / (2.0 * 128 * 128)), worst);
  }
  return 0;
}
