// The sky on the GPU: the host side of shaders/sky/*.comp. The shaders build the tables of
// SkyModel (src/env/sky.cpp) with the same per-point math (ibl/shared/sky.h) and the same
// marches, then the panorama; the host supplies the physical constants and paints the sun.
#include <array>

#include <glm/vec4.hpp>

#include "gpu/buffers.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/gpu/compute.hpp"

namespace ibl::gpu {

namespace {

// The atmosphere as shaders/sky/atmosphere.glsl reads it (binding 0, std430).
struct SkyConstants {
  glm::vec4 sunAndRadius;  // the direction toward the sun; the observer's distance from the center
  glm::vec4 shape0;        // bottomRadius, topRadius, rayleighHeight, mieHeight
  glm::vec4 shape1;        // ozoneCenter, ozoneHalfWidth; ground albedo; Mie's asymmetry g
  glm::vec4 flags;         // the horizon's elevation; 1 with multiple scattering
  std::array<glm::vec4, kSkyBands> bands;  // rayleigh, mieScattering, mieExtinction, ozone
  std::array<glm::vec4, kSkyBands> light;  // solar irradiance at the top; sky on the ground
  std::array<glm::vec4, kSkyBands> xyz;    // skyBandXyz
};

SkyConstants skyConstants(const SkyParameters& p) {
  const shared::AtmosphereShape shape = skyAtmosphereShape();
  const AtmosphereCoefficients c = atmosphereCoefficients(p);
  const float radius = shape.bottomRadius + p.altitude;
  SkyConstants k{};
  k.sunAndRadius = glm::vec4(sunDirection(p.sunElevation, p.sunAzimuth), radius);
  k.shape0 = {shape.bottomRadius, shape.topRadius, shape.rayleighHeight, shape.mieHeight};
  k.shape1 = {shape.ozoneCenter, shape.ozoneHalfWidth, p.groundAlbedo, skyMieAsymmetry()};
  k.flags = {shared::horizonElevation(shape, radius), p.multipleScattering ? 1.0f : 0.0f, 0.0f,
             0.0f};
  for (int i = 0; i < kSkyBands; ++i) {
    k.bands[i] = {c.rayleighScattering[i], c.mieScattering[i], c.mieExtinction[i],
                  c.ozoneAbsorption[i]};
    k.light[i] = {solarIrradianceAtTop()[i], 0.0f, 0.0f, 0.0f};
    k.xyz[i] = glm::vec4(glm::vec3(skyBandXyz(i)), 0.0f);
  }
  return k;
}

}  // namespace

Image skyPanorama(Context& context, const SkyParameters& p, int width, int height, bool paintSun) {
  checkSkyParameters(p, "sky");
  checkSkyPanoramaSize(width, height);
  SkyConstants k = skyConstants(p);
  Buffer constants(context, sizeof(SkyConstants));
  constants.upload(&k, sizeof(k));
  constexpr std::size_t kDepthTexels = std::size_t{shared::kDepthTableMu} * shared::kDepthTableR;
  constexpr std::size_t kMultipleTexels =
      std::size_t{shared::kMultipleTableMu} * shared::kMultipleTableR;
  Buffer depth(context, kDepthTexels * sizeof(glm::vec4));
  Buffer multiple(context, kMultipleTexels * kSkyBands * sizeof(float));
  dispatch(context, "sky_depth", {&constants, &depth, &multiple}, {}, groups(kDepthTexels, 64));
  dispatch(context, "sky_multiple", {&constants, &depth, &multiple}, {},
           groups(kMultipleTexels, 64));
  if (p.groundAlbedo > 0.0f) {
    // The sky's light on the ground, cell by cell; added up here ring by ring, as the CPU does.
    constexpr int kCells = shared::kGroundSkyRings * shared::kGroundSkySectors;
    Buffer cells(context, std::size_t{kCells} * kSkyBands * sizeof(float));
    dispatch(context, "sky_ground", {&constants, &depth, &multiple, &cells}, {},
             groups(kCells, 64));
    const auto values = cells.read<float>(std::size_t{kCells} * kSkyBands);
    for (int ring = 0; ring < shared::kGroundSkyRings; ++ring) {
      Spectrum row{};
      for (int sector = 0; sector < shared::kGroundSkySectors; ++sector)
        for (int i = 0; i < kSkyBands; ++i)
          row[i] += values[static_cast<std::size_t>(ring * shared::kGroundSkySectors + sector) *
                               kSkyBands +
                           i];
      for (int i = 0; i < kSkyBands; ++i) k.light[i].y += row[i];
    }
    constants.upload(&k, sizeof(k));
  }
  constexpr std::size_t kViewTexels =
      std::size_t{2} * shared::kSkyViewRows * shared::kSkyViewAzimuths;
  Buffer view(context, kViewTexels * sizeof(glm::vec4));
  dispatch(context, "sky_view", {&constants, &depth, &multiple, &view}, {},
           groups(kViewTexels, 64));
  const std::size_t pixelCount = static_cast<std::size_t>(width) * height;
  Buffer pixels(context, pixelCount * sizeof(glm::vec4));
  const struct {
    glm::vec4 sunAndHorizon;
    std::uint32_t width, height;
  } params{glm::vec4(glm::vec3(k.sunAndRadius), k.flags.x), static_cast<std::uint32_t>(width),
           static_cast<std::uint32_t>(height)};
  dispatch(context, "sky_panorama", {&view, &pixels}, bytesOf(params),
           groups(static_cast<std::size_t>(width), 8), groups(static_cast<std::size_t>(height), 8));
  const auto texels = pixels.read<glm::vec4>(pixelCount);
  Image image(width, height);
  for (std::size_t i = 0; i < pixelCount; ++i) image.pixels[i] = glm::vec3(texels[i]);
  if (paintSun) paintSunDisk(image, skySun(p));
  return image;
}

}  // namespace ibl::gpu
