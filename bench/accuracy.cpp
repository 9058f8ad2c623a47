// Accuracy report: each prefiltered specular level and the irradiance cube of the default
// bake, against brute-force references (direct quadrature over every texel of the 256^2
// source cube), as relative RMSE of luminance over texels, for the bundled HDRIs.
//   ibl_accuracy [hdri ...]     (default: sunset park studio)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "ibl/color.hpp"
#include "ibl/environment.hpp"
#include "ibl/prefilter.hpp"
#include "ibl/resample.hpp"

namespace {

using Clock = std::chrono::steady_clock;

// Texel directions of a level: all of them, or a fixed random subset of `limit`.
std::vector<std::pair<int, glm::ivec2>> pickTexels(int size, std::size_t limit) {
  std::vector<std::pair<int, glm::ivec2>> all;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) all.push_back({f, {x, y}});
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

double levelError(const std::array<ibl::Image, 6>& level, const std::array<ibl::Image, 6>& source,
                  float roughness, bool irradiance) {
  const int size = level[0].width;
  const auto texels = pickTexels(size, 3000);
  std::vector<glm::vec3> dirs;
  for (const auto& [f, p] : texels) dirs.push_back(ibl::texelDirection(f, p.x, p.y, size));
  const auto ref = irradiance ? ibl::irradianceDirections(source, dirs)
                              : ibl::prefilterDirections(source, dirs, roughness,
                                                         ibl::PrefilterWeight::Standard);
  std::vector<float> a, b;
  for (std::size_t i = 0; i < texels.size(); ++i) {
    a.push_back(ibl::luminance(level[texels[i].first].at(texels[i].second.x, texels[i].second.y)));
    b.push_back(ibl::luminance(ref[i]));
  }
  return relativeRmse(a, b);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) names.push_back(argv[i]);
  if (names.empty()) names = {"sunset", "park", "studio"};
  for (const auto& name : names) {
    const auto env =
        ibl::loadEnvironment(std::string(IBL_BENCH_DATA) + "/hdri/" + name + ".exr").environment;
    ibl::CubeMap source = ibl::resampleToCube(env, 256);
    ibl::buildMipChain(source);
    fmt::print("{} (256^2 source, relative RMSE of luminance against the brute-force reference)\n",
               name);
    for (auto method : {ibl::PrefilterMethod::Direct, ibl::PrefilterMethod::Sampled}) {
      ibl::PrefilterOptions options;
      options.method = method;
      std::vector<ibl::LevelMethod> methods;
      const auto t0 = Clock::now();
      const ibl::CubeMap specular = ibl::prefilterGgx(source, options, &methods);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      fmt::print("  specular, {} ({:.0f} ms)\n",
                 method == ibl::PrefilterMethod::Direct
                     ? "direct (default)"
                     : "filtered importance sampling, 64 samples",
                 ms);
      for (int m = 1; m < specular.levelCount(); ++m) {
        const double e =
            levelError(specular.levels[m], source.levels[0], methods[m].roughness, false);
        fmt::print("    level {}  {:3}^2  r = {:.3f}  {:8} source {:3}^2  {:7.3f} %\n", m,
                   specular.levels[m][0].width, methods[m].roughness, methods[m].method,
                   methods[m].sourceSize, 100.0 * e);
      }
    }
    const auto t1 = Clock::now();
    const ibl::CubeMap irradiance =
        ibl::convolveIrradiance(source, 32, ibl::levelOfSize(source, 32));
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t1).count();
    fmt::print("  irradiance 32^2, direct over the 32^2 level ({:.0f} ms)  {:7.3f} %\n", ms,
               100.0 * levelError(irradiance.levels[0], source.levels[0], 0.0f, true));
  }
  return 0;
}
