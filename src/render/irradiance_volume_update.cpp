// The irradiance volume's live update on the CPU (Majercik et al. 2019, section 5): rays from
// every probe, shaded with the split sum's diffuse and the volume itself, blended into the
// texels with hysteresis. The viewer's update runs the same rules (ibl/shared/irradiance_volume.h).
#include <cmath>
#include <span>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "ibl/bake/dfg.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/render/irradiance_volume.hpp"
#include "path_tracer.hpp"
#include "ray_tracer.hpp"
#include "sampler.hpp"
#include "shadow_rays.hpp"

namespace ibl {

// A unit quaternion from three uniform numbers (Shoemake 1992, "Uniform Random Rotations",
// Graphics Gems III).
glm::mat3 volumeFrameRotation(unsigned seed, unsigned frame) {
  Sampler sampler(seed, 0x9E3779B9u + frame);
  sampler.startSample(0);
  const glm::vec2 a = sampler.uniform2();
  const float u3 = sampler.uniform2().x;
  const float r1 = std::sqrt(1.0f - a.x), r2 = std::sqrt(a.x);
  const float t1 = 2.0f * shared::kPi * a.y, t2 = 2.0f * shared::kPi * u3;
  const glm::quat q(r2 * std::cos(t2), r1 * std::sin(t1), r1 * std::cos(t1), r2 * std::sin(t2));
  return glm::mat3_cast(glm::normalize(q));
}

void updateVolume(const Scene& scene, IrradianceVolume& volume, const BakeResult& bake,
                  const BakeOptions& bakeOptions, const RenderOptions& shading,
                  const VolumeUpdateOptions& options, unsigned frame) {
  const VolumeGrid& g = volume.grid;
  const int count = volumeProbeCount(g);
  const int rays = std::max(1, options.raysPerProbe);
  const glm::mat3 rotation = volumeFrameRotation(volume.capture.seed, frame);
  const float farthest = 2.0f * glm::length(g.spacing);
  const RayTracer tracer(scene);
  // The hits are lit by the volume as it was before this frame.
  const IrradianceVolume previous = volume;
  RenderOptions o = shading;
  o.mode = RenderMode::SplitSum;
  o.only = ShadingTerms::Diffuse;
  o.volume = &previous;
  o.probes = nullptr;
  o.screenOcclusion = nullptr;
  o.screenReflection = nullptr;
  // The frame's directions (the same from every probe), and per probe and ray what came back:
  // the radiance, and the distance's two moments.
  std::vector<glm::vec3> directions(static_cast<std::size_t>(rays));
  for (int i = 0; i < rays; ++i)
    directions[static_cast<std::size_t>(i)] = shared::volumeRayDirection(i, rays, rotation);
  const std::size_t samples = static_cast<std::size_t>(count) * rays;
  std::vector<glm::vec3> radiance(samples), moments(samples);
  parallelFor(0, count, [&](int probe) {
    const ProbeRelocation& r = volume.probes[static_cast<std::size_t>(probe)];
    if (!r.on) return;
    const glm::vec3 origin = volumeProbePosition(g, probe) + r.offset;
    Sampler sampler(volume.capture.seed, (static_cast<std::uint64_t>(frame) << 32) + probe);
    std::vector<glm::vec3> visibility(scene.lights.size());
    for (int i = 0; i < rays; ++i) {
      const std::size_t at = static_cast<std::size_t>(probe) * rays + i;
      const Ray ray{origin, directions[static_cast<std::size_t>(i)]};
      // The ray sees through the surfaces that transmit, as the shadows do: what lies behind
      // them, times the share they let through (transmissiveTransmittance; their own diffuse is
      // left out), and they hide nothing from the volume's visibility test.
      const RayTracer::Hit hit = firstOpaqueHit(tracer, ray);
      const float distance = hit.found ? std::min(hit.t, farthest) : farthest;
      moments[at] = glm::vec3(distance, distance * distance, 0.0f);
      const glm::vec3 through = transmissiveTransmittance(
          scene, tracer, origin, ray.direction, hit.found ? hit.t * (1.0f - 1e-4f) : INFINITY);
      if (!hit.found) {
        radiance[at] = o.environmentLight ? through * sampleBilinear(bake.source, 0, ray.direction)
                                          : glm::vec3(0.0f);
        continue;
      }
      SurfacePoint p = surfaceAt(scene, tracer, hit, ray);
      if (volume.capture.metalsAsDiffuse) p = metalAsDiffuse(p);
      const glm::vec3 view = -ray.direction;
      sampler.startSample(static_cast<std::uint32_t>(i));
      for (std::size_t l = 0; l < scene.lights.size(); ++l)
        visibility[l] =
            rayTracedVisibility(scene, tracer, scene.lights[l], p.position, p.normal, 1, sampler);
      radiance[at] = through * (shadeSplitSum(p, view, bake, bakeOptions, o) +
                                shadeLightsRealTime(p, p.position, view, scene.lights, bake.dfg, o,
                                                    1.0f, visibility));
    }
  });
  // Each texel: the frame's weighted mean blended with what it held.
  const auto blendTiles = [&](Image& atlas, int texels, const std::vector<glm::vec3>& values,
                              double power) {
    parallelFor(0, count, [&](int probe) {
      if (!volume.probes[static_cast<std::size_t>(probe)].on) return;
      const std::span<const glm::vec3> probeValues(
          values.data() + static_cast<std::size_t>(probe) * rays, static_cast<std::size_t>(rays));
      const int perRow = g.counts.x * g.counts.y;
      const glm::ivec2 tile = glm::ivec2(probe % perRow, probe / perRow) * (texels + 2);
      for (int y = 0; y < texels; ++y)
        for (int x = 0; x < texels; ++x) {
          const glm::vec2 uv = (glm::vec2(x, y) + 0.5f) / static_cast<float>(texels) * 2.0f - 1.0f;
          const LobeSums s =
              cosineLobeSums(shared::octahedralDecode(uv), directions, {}, probeValues, power);
          glm::vec3& texel = atlas.at(tile.x + 1 + x, tile.y + 1 + y);
          texel = shared::volumeBlend(texel, glm::vec3(s.weighted), static_cast<float>(s.total),
                                      options.hysteresis);
        }
    });
    fillVolumeBorders(atlas, g, texels);
  };
  blendTiles(volume.irradiance, g.irradianceTexels, radiance, 1.0);
  blendTiles(volume.distance, g.distanceTexels, moments, shared::kVolumeDistanceSharpness);
}

}  // namespace ibl
