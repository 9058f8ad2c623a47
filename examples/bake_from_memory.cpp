// Embedding ibl: bake an environment held in memory (pixels this program owns, no file), then
// shade a surface point with the result, the way a real-time renderer would.
//
// Build it against an installed ibl (docs/install.md):
//   cmake -S examples -B build-examples -G Ninja -DCMAKE_PREFIX_PATH=<prefix>
//   ninja -C build-examples && build-examples/bake_from_memory
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>

#include <glm/geometric.hpp>

#include "ibl/bake/bake.hpp"
#include "ibl/core/error.hpp"
#include "ibl/core/version.hpp"
#include "ibl/math/sh.hpp"
#include "ibl/render/renderer.hpp"

int main() {
  try {
    // A sky brighter above than below: radiance L(d) = 1 + 0.5 d.y (relative units), as a 2:1
    // latitude-longitude image, row 0 looking straight up.
    const int width = 256, height = 128;
    ibl::Image sky(width, height);
    for (int y = 0; y < height; ++y) {
      const double theta = std::numbers::pi * (y + 0.5) / height;  // from +Y
      const auto radiance = static_cast<float>(1.0 + 0.5 * std::cos(theta));
      for (int x = 0; x < width; ++x) sky.at(x, y) = glm::vec3(radiance);
    }
    ibl::Environment environment;
    environment.layout = ibl::Layout::Equirect;
    environment.equirect = std::move(sky);

    // Small maps: this runs in a fraction of a second.
    ibl::BakeOptions options;
    options.specular.size = 64;
    options.irradianceSize = 16;
    options.dfgSize = 32;
    options.dfgSamples = 128;
    const ibl::BakeResult bake = ibl::bakeEnvironment(environment, options);

    // Irradiance on an upward plane (W/m^2 for radiance in W/(sr m^2)): exactly
    // pi (1 + 0.5 * 2/3) for this sky, since SH9 holds a linear function of the direction
    // without loss.
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const glm::vec3 irradiance = ibl::irradianceSh9(bake.sh, up);
    std::printf("ibl %s: irradiance on an upward plane = %.5f (exact %.5f)\n", ibl::kVersion,
                irradiance.x, std::numbers::pi * (1.0 + 0.5 * 2.0 / 3.0));

    // A white, fairly rough dielectric facing up, seen from 45 degrees: the split sum's
    // radiance toward the viewer.
    ibl::SurfacePoint point;
    point.normal = up;
    point.baseColor = glm::vec3(1.0f);
    point.metallic = 0.0f;
    point.roughness = 0.6f;
    const glm::vec3 view = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
    const glm::vec3 shaded = ibl::shadeSplitSum(point, view, bake, options, ibl::RenderOptions{});
    std::printf("shaded radiance = %.5f %.5f %.5f\n", shaded.x, shaded.y, shaded.z);
    return 0;
  } catch (const std::exception& e) {  // ibl::Error: "<what>: <problem>"
    std::fprintf(stderr, "bake_from_memory: %s\n", e.what());
    return 1;
  }
}
