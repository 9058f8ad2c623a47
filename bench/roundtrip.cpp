// Sharpness and energy of resampling: each HDRI goes equirect -> cube -> equirect at its own
// resolution (the cube about 0.8x as dense as the panorama, as a 512^2 cube is for a 2K
// panorama), with `ibl`'s area-weighted resampling and with plain bilinear point sampling both
// ways. Printed per HDRI: the median and mean per-pixel relative error of luminance (pixels
// with luminance above 1e-3 of the mean), and the power of the cube and of the round trip
// relative to the panorama's.
//   ibl_roundtrip [hdri ...]     (default: all bundled HDRIs)
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "ibl/core/parallel.hpp"
#include "ibl/core/stats.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/equirect.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/math/color.hpp"

namespace {

using namespace ibl;

struct RoundTrip {
  double median = 0.0, mean = 0.0;
};

RoundTrip compare(const Image& result, const Image& original) {
  double meanLum = 0.0;
  for (const auto& p : original.pixels) meanLum += luminance(p);
  meanLum /= static_cast<double>(original.pixels.size());
  std::vector<double> errors;
  for (std::size_t i = 0; i < original.pixels.size(); ++i) {
    const double ref = luminance(original.pixels[i]);
    if (ref <= 1e-3 * meanLum) continue;
    errors.push_back(std::abs(luminance(result.pixels[i]) - ref) / ref);
  }
  RoundTrip r;
  std::sort(errors.begin(), errors.end());
  r.median = errors[errors.size() / 2];
  for (double e : errors) r.mean += e;
  r.mean /= static_cast<double>(errors.size());
  return r;
}

// Point sampling with bilinear interpolation, both ways: the sharpness baseline.
Image bilinearRoundTrip(const Image& equirect, int size) {
  CubeMap cube(size, 1);
  parallelFor(0, kFaceCount * size, [&](int row) {
    const int face = row / size, y = row % size;
    for (int x = 0; x < size; ++x) {
      const float sc = (static_cast<float>(x) + 0.5f) * 2.0f / static_cast<float>(size) - 1.0f;
      const float tc = (static_cast<float>(y) + 0.5f) * 2.0f / static_cast<float>(size) - 1.0f;
      cube.levels[0][face].at(x, y) = sampleEquirect(equirect, faceToDirection(face, sc, tc));
    }
  });
  Image out(equirect.width, equirect.height);
  parallelFor(0, out.height, [&](int y) {
    for (int x = 0; x < out.width; ++x)
      out.at(x, y) = sampleBilinear(
          cube, 0,
          equirectToDirection((static_cast<float>(x) + 0.5f) / static_cast<float>(out.width),
                              (static_cast<float>(y) + 0.5f) / static_cast<float>(out.height)));
  });
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> names(argv + 1, argv + argc);
  if (names.empty()) names = {"sunset", "park", "studio", "night", "apartment"};
  fmt::print("{:10} {:>6} {:>14} {:>14} {:>14} {:>14} {:>10} {:>10}\n", "hdri", "cube",
             "median (ibl)", "median (bilin)", "mean (ibl)", "mean (bilin)", "power cube",
             "round trip");
  for (const auto& name : names) {
    const std::string path = std::string(IBL_BENCH_DATA) + "/hdri/" + name + ".exr";
    const Environment env = loadEnvironment(path).environment;
    const Image& original = env.equirect;
    const int size = std::max(1, static_cast<int>(std::lround(original.height * 0.5)));
    Environment cube;
    cube.layout = Layout::Cube;
    cube.cube = resampleToCube(env, size);
    const Image back = resampleToEquirect(cube, original.width);
    const RoundTrip ours = compare(back, original);
    const RoundTrip bilinear = compare(bilinearRoundTrip(original, size), original);
    const auto power = [&](const Environment& e) {
      return luminance(glm::vec3(radiantIntegral(e))) / luminance(glm::vec3(radiantIntegral(env))) -
             1.0;
    };
    Environment backEnv;
    backEnv.equirect = back;
    fmt::print("{:10} {:>6} {:>13.2f}% {:>13.2f}% {:>13.2f}% {:>13.2f}% {:>+9.4f}% {:>+9.4f}%\n",
               name, size, 100 * ours.median, 100 * bilinear.median, 100 * ours.mean,
               100 * bilinear.mean, 100 * power(cube), 100 * power(backEnv));
  }
}
