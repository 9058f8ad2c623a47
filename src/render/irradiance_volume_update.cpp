// The irradiance volume's live update on the CPU (Majercik et al. 2019, section 5): rays from
// every probe, shaded with the split sum's diffuse and the volume itself, blended into the
// texels with hysteresis. The viewer's update runs the same rules (ibl/shared/irradiance_volume.h).
#include <cmath>
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

namespace {

struct RayResult {
  glm::vec3 direction{0.0f};
  glm::vec3 radiance{0.0f};
  float distance = 0.0f;
};

}  // namespace

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
  std::vector<RayResult> results(static_cast<std::size_t>(count) * rays);
  parallelFor(0, count, [&](int probe) {
    const ProbeRelocation& r = volume.probes[static_cast<std::size_t>(probe)];
    if (!r.on) return;
    const glm::vec3 origin = volumeProbePosition(g, probe) + r.offset;
    Sampler sampler(volume.capture.seed, (static_cast<std::uint64_t>(frame) << 32) + probe);
    std::vector<float> visibility(scene.lights.size());
    for (int i = 0; i < rays; ++i) {
      RayResult& out = results[static_cast<std::size_t>(probe) * rays + i];
      out.direction = shared::volumeRayDirection(i, rays, rotation);
      const Ray ray{origin, out.direction};
      const RayTracer::Hit hit = tracer.intersect(ray);
      if (!hit.found) {
        out.distance = farthest;
        out.radiance =
            o.environmentLight ? sampleBilinear(bake.source, 0, ray.direction) : glm::vec3(0.0f);
        continue;
      }
      out.distance = std::min(hit.t, farthest);
      SurfacePoint p = surfaceAt(scene, tracer, hit, ray);
      if (volume.capture.metalsAsDiffuse) p = metalAsDiffuse(p);
      const glm::vec3 view = -ray.direction;
      sampler.startSample(static_cast<std::uint32_t>(i));
      for (std::size_t l = 0; l < scene.lights.size(); ++l)
        visibility[l] =
            rayTracedVisibility(tracer, scene.lights[l], p.position, p.normal, 1, sampler);
      const glm::vec2 dfg(
          sampleDfgLut(bake.dfg, std::max(glm::dot(p.normal, view), 1e-4f), p.roughness));
      out.radiance =
          shadeSplitSum(p, view, bake, bakeOptions, o) +
          shadeLightsRealTime(p, p.position, view, scene.lights, dfg, o, 1.0f, visibility);
    }
  });
  // Each texel: the frame's weighted mean blended with what it held.
  const auto blendTiles = [&](Image& atlas, int texels, bool distances) {
    parallelFor(0, count, [&](int probe) {
      if (!volume.probes[static_cast<std::size_t>(probe)].on) return;
      const RayResult* probeRays = &results[static_cast<std::size_t>(probe) * rays];
      const int perRow = g.counts.x * g.counts.y;
      const glm::ivec2 tile = glm::ivec2(probe % perRow, probe / perRow) * (texels + 2);
      for (int y = 0; y < texels; ++y)
        for (int x = 0; x < texels; ++x) {
          const glm::vec2 uv = (glm::vec2(x, y) + 0.5f) / static_cast<float>(texels) * 2.0f - 1.0f;
          const glm::vec3 n = shared::octahedralDecode(uv);
          glm::dvec3 sum(0.0);
          double total = 0.0;
          for (int i = 0; i < rays; ++i) {
            const double c = glm::dot(n, probeRays[i].direction);
            if (c <= 0.0) continue;
            const double w = distances ? std::pow(c, double{shared::kVolumeDistanceSharpness}) : c;
            const glm::dvec3 value =
                distances ? glm::dvec3(probeRays[i].distance,
                                       double(probeRays[i].distance) * probeRays[i].distance, 0.0)
                          : glm::dvec3(probeRays[i].radiance);
            sum += w * value;
            total += w;
          }
          glm::vec3& texel = atlas.at(tile.x + 1 + x, tile.y + 1 + y);
          texel = shared::volumeBlend(texel, glm::vec3(sum), static_cast<float>(total),
                                      options.hysteresis);
        }
    });
    fillVolumeBorders(atlas, g, texels);
  };
  blendTiles(volume.irradiance, g.irradianceTexels, false);
  blendTiles(volume.distance, g.distanceTexels, true);
}

}  // namespace ibl
