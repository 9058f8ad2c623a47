#include "ibl/render/renderer.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "ibl/bake/dfg.hpp"
#include "ibl/bake/prefilter.hpp"
#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/math/color.hpp"
#include "ibl/math/sampling.hpp"
#include "ibl/render/irradiance_volume.hpp"
#include "ibl/render/light_sampling.hpp"
#include "ibl/render/ltc.hpp"
#include "ibl/render/probe.hpp"
#include "ibl/shared/lights.h"
#include "ibl/shared/screen_space_reflections.h"
#include "ibl/shared/shadows.h"
#include "ibl/shared/specular_antialiasing.h"
#include "ibl/shared/split_sum.h"
#include "path_tracer.hpp"
#include "ray_tracer.hpp"
#include "shadow_rays.hpp"

namespace ibl {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Ambient occlusion: the cosine-weighted share of `rays` hemisphere rays from p that meet
// nothing within `distance` (the visibility the split sum's AO stands for).
float ambientOcclusion(const RayTracer& tracer, const SurfacePoint& p, int rays, float distance,
                       Sampler& sampler) {
  const glm::mat3 frame = tangentFrame(p.normal);
  const glm::vec3 origin = p.position + p.normal * 1e-4f * std::max(1.0f, glm::length(p.position));
  int open = 0;
  for (int i = 0; i < rays; ++i) {
    const glm::vec3 w = frame * sampleCosineHemisphere(sampler.uniform2());
    if (!tracer.occluded(origin, w, distance)) ++open;
  }
  return static_cast<float>(open) / static_cast<float>(rays);
}

}  // namespace

shared::SplitSumSwitches splitSumSwitches(const RenderOptions& o) {
  shared::SplitSumSwitches s;
  s.terms = o.only == ShadingTerms::Diffuse ? 1 : (o.only == ShadingTerms::Specular ? 2 : 0);
  s.multipleScattering = o.multipleScattering != MultipleScattering::Off;
  s.dominantDirections = o.dominantDirections;
  s.specularOcclusion = o.specularOcclusion;
  s.disneyDiffuse = o.diffuse == DiffuseModel::Disney;
  s.ltcAreaLights = o.areaLights == AreaLightModel::Ltc;
  s.sheenVisibility = static_cast<int>(o.sheenVisibility);
  s.specularMicroOcclusion = o.specularMicroOcclusion;
  s.multiBounceOcclusion = o.screenAmbientOcclusion.enabled;
  return s;
}

// The emission is left for the caller to add.
shared::SplitSumMaterial splitSumMaterial(const SurfacePoint& p, float occlusion) {
  shared::SplitSumMaterial m;
  m.baseColor = p.baseColor;
  m.metallic = p.metallic;
  m.roughness = p.roughness;
  m.occlusion = occlusion;
  m.emissive = glm::vec3(0.0f);
  m.ior = p.ior;
  m.specular = p.specular;
  m.specularColor = p.specularColor;
  m.clearcoat = p.clearcoat;
  m.clearcoatRoughness = p.clearcoatRoughness;
  m.clearcoatNormal = p.clearcoatNormal;
  m.iridescence = p.iridescence;
  m.iridescenceIor = p.iridescenceIor;
  m.iridescenceThickness = p.iridescenceThickness;
  m.anisotropy = p.anisotropy;
  m.anisotropyTangent = p.anisotropyTangent;
  m.transmission = p.transmission;
  m.thickness = p.volume ? p.thickness : 0.0f;
  m.attenuation = p.attenuation;
  return m;
}

namespace {

// What a clear coat (KHR_materials_clearcoat) lets through of the layers below it toward `view`.
float belowCoat(const SurfacePoint& p, glm::vec3 view) {
  return p.clearcoat > 0.0f
             ? 1.0f - shared::clearcoatWeight(p.clearcoat, glm::dot(p.clearcoatNormal, view))
             : 1.0f;
}

}  // namespace

glm::vec3 shadeSplitSum(const SurfacePoint& p, glm::vec3 view, const BakeResult& bake,
                        const BakeOptions& bakeOptions, const RenderOptions& o) {
  // The formulas are ibl/shared/split_sum.h (the viewer's shader calls the same); only the
  // three lookups are the CPU's own: seam-aware trilinear and bilinear, the DFG table.
  const shared::SplitSumSwitches s = splitSumSwitches(o);
  const shared::SplitSumMaterial m = splitSumMaterial(p, p.occlusion);
  shared::SplitSumLookup look = shared::splitSumLookup(p.normal, view, p.roughness, s);
  look = shared::anisotropicLookup(look, p.normal, view, m, s);
  if (p.bentNormal != glm::vec3(0.0f))
    look = shared::bendDiffuseLookup(look, p.bentNormal, view, p.roughness, s);
  // The isotropic tables at the lobe's albedo-equivalent roughness (KHR_materials_anisotropy).
  const float lobeRoughness = shared::tableRoughness(m);
  glm::vec3 dfg = sampleDfgLut(bake.dfg, look.NoV, lobeRoughness);
  // Disney's diffuse (the table's third channel) at the material's own roughness.
  if (lobeRoughness != p.roughness) dfg.z = sampleDfgLut(bake.dfg, look.NoV, p.roughness).z;
  glm::vec3 irradiance(0.0f);
  // Local probes first (smallest influence first), the distant environment for the rest.
  float distant = 1.0f, distantDiffuse = 1.0f;
  // The prefiltered light along `direction` at `roughness` (the coat's lobe reads it too);
  // `local` receives the probes' lighting when there are probes.
  const auto prefilteredLight = [&](glm::vec3 direction, glm::vec3 diffuseDirection,
                                    float roughness, ProbeLighting* local) {
    glm::vec3 light(0.0f);
    float rest = 1.0f;
    if (o.probes && !o.probes->empty()) {
      const ProbeLighting l =
          lookupProbes(*o.probes, p.position, direction, diffuseDirection, roughness, o);
      light = l.prefiltered;
      rest = 1.0f - l.coverage;
      if (local) *local = l;
    }
    if (o.environmentLight && rest > 0.0f && o.only != ShadingTerms::Diffuse) {
      const float lod = specularLodForRoughness(roughness, bake.specular.levelCount(),
                                                bakeOptions.specular.mapping);
      light += rest * sampleTrilinear(bake.specular, lod, direction);
    }
    return light;
  };
  ProbeLighting local{};
  glm::vec3 prefiltered =
      prefilteredLight(look.specularDirection, look.diffuseDirection, p.roughness, &local);
  if (o.probes && !o.probes->empty()) {
    irradiance = local.irradiance;
    distant = 1.0f - local.coverage;
    distantDiffuse = 1.0f - local.diffuseCoverage;
  }
  const auto distantIrradiance = [&] {
    return o.irradiance == IrradianceSource::Cube
               ? sampleBilinear(bake.irradiance, 0, look.diffuseDirection)
               : irradianceSh9(bake.sh, look.diffuseDirection) / kPi;
  };
  if (o.environmentLight && distantDiffuse > 0.0f && o.only != ShadingTerms::Specular)
    irradiance += distantDiffuse * distantIrradiance();
  float specularScale = 1.0f;
  if (o.volume) {
    // The volume gives the diffuse light where it covers, and normalizes the specular of what
    // it replaces by its irradiance (ibl/shared/irradiance_volume.h).
    const float cover = shared::volumeCoverage(o.volume->grid, p.position);
    if (cover > 0.0f) {
      const glm::vec3 volume =
          lookupVolume(*o.volume, p.position, p.normal, view, look.diffuseDirection);
      // Under --only specular the diffuse above was not gathered: the ratio is to the distant
      // environment's.
      const glm::vec3 source = o.only == ShadingTerms::Specular
                                   ? (o.environmentLight ? distantIrradiance() : glm::vec3(0.0f))
                                   : irradiance;
      specularScale = shared::volumeSpecularScale(volume, source, cover);
      prefiltered *= specularScale;
      irradiance = glm::mix(irradiance, volume, cover);
    }
  }
  shared::SplitSumSwitches composed = s;
  if (p.screenReflection != glm::vec4(0.0f) && o.only != ShadingTerms::Diffuse) {
    // Lagarde & de Rousiers 2014, 4.9.5: the screen's reflection first, the probes for the rest.
    prefiltered = shared::composeScreenReflection(p.screenReflection, prefiltered,
                                                  shared::probeSpecularOcclusion(s, look.NoV, m));
    composed.specularOcclusion = false;
  }
  glm::vec3 below =
      o.only == ShadingTerms::Sheen
          ? glm::vec3(0.0f)
          : shared::splitSumRadiance(m, look.NoV, dfg, prefiltered, irradiance, composed);
  if (p.transmission > 0.0f && o.only != ShadingTerms::Diffuse && o.only != ShadingTerms::Sheen) {
    // The light straight through the surface, blurred by the transmission's roughness.
    glm::vec3 transmitted =
        specularScale *
        prefilteredLight(-view, -view, shared::transmissionRoughness(p.roughness, p.ior), nullptr);
    if (const TransmissionFrame* frame = o.transmissionFrame) {
      // The opaque surfaces behind, where the refracted ray leaves the volume (the glTF Sample
      // Viewer's); the environment where they leave the frame uncovered.
      const glm::vec3 exit =
          p.position + shared::volumeExitOffset(p.normal, view, m.thickness, p.ior);
      const float lod = shared::transmissionFrameLod(frame->projection.size.x, p.roughness, p.ior);
      transmitted = shared::behindSurface(frame->at(exit, lod), transmitted);
    }
    below += shared::transmissionRadiance(m, look.NoV, glm::vec2(dfg), transmitted, s);
  }
  if (p.sheenColor != glm::vec3(0.0f)) {
    if (!bake.sheen || !bake.sheenDfg)
      fail("render",
           "a material has a sheen (KHR_materials_sheen) but the bake has none; bake "
           "with --sheen");
    // The sheen prefilter stops at kMinSheenRoughness; the reference's material does too.
    const float rs = std::max(p.sheenRoughness, kMinSheenRoughness);
    const float e = sampleDfgLut(*bake.sheenDfg, look.NoV, rs).x;
    below *= shared::sheenAlbedoScaling(p.sheenColor, e);
    if (o.environmentLight && distant > 0.0f && o.only != ShadingTerms::Diffuse &&
        o.only != ShadingTerms::Specular) {
      // The sheen chain has the specular chain's levels and mapping. It is read at the normal,
      // not at the reflection as the glTF Sample Viewer and Filament do: the Charlie lobe lies
      // along the surface's horizon whatever the view, and against the reference the normal is
      // closer (docs/targets.md: 6.6 % against 10.2 % on a smooth sky).
      const float lod =
          specularLodForRoughness(rs, bake.sheen->levelCount(), bakeOptions.specular.mapping);
      const glm::vec3 prefilteredSheen = distant * sampleTrilinear(*bake.sheen, lod, p.normal);
      below += shared::sheenRadiance(p.sheenColor, e, prefilteredSheen) * p.occlusion;
    }
  }
  if (p.clearcoat > 0.0f) below *= belowCoat(p, view);
  if (p.clearcoat > 0.0f && o.only != ShadingTerms::Sheen) {
    // The coat over all of it (its emission already attenuated by surfaceAt): its lobe reads the
    // same light at its own normal and roughness; the screen-space reflection is the base's alone.
    const shared::SplitSumLookup coat =
        shared::splitSumLookup(p.clearcoatNormal, view, p.clearcoatRoughness, s);
    const glm::vec3 coatDfg = sampleDfgLut(bake.dfg, coat.NoV, p.clearcoatRoughness);
    const glm::vec3 light =
        specularScale * prefilteredLight(coat.specularDirection, coat.specularDirection,
                                         p.clearcoatRoughness, nullptr);
    below += shared::clearcoatRadiance(m, coat.NoV, glm::vec2(coatDfg), light, s);
  }
  return below + p.emissive;
}

glm::vec3 shadeLightsRealTime(const SurfacePoint& p, glm::vec3 position, glm::vec3 view,
                              const std::vector<Light>& lights, const Image& dfgTable,
                              const RenderOptions& o, float belowScale,
                              const std::vector<glm::vec3>& visibility) {
  const shared::SplitSumSwitches s = splitSumSwitches(o);
  // Ambient occlusion darkens indirect light only.
  const shared::SplitSumMaterial m = splitSumMaterial(p, 1.0f);
  // The isotropic tables at the lobe's albedo-equivalent roughness (KHR_materials_anisotropy).
  const float lobeRoughness = shared::tableRoughness(m);
  const glm::vec2 dfg(
      sampleDfgLut(dfgTable, std::max(glm::dot(p.normal, view), 1e-4f), lobeRoughness));
  // KHR_materials_clearcoat: the coat's lobe at its normal and roughness, over the rest.
  const bool coat = p.clearcoat > 0.0f && o.only != ShadingTerms::Sheen;
  const float coatNoV = std::max(glm::dot(p.clearcoatNormal, view), 1e-4f);
  const glm::vec2 coatDfg =
      coat ? glm::vec2(sampleDfgLut(dfgTable, coatNoV, p.clearcoatRoughness)) : glm::vec2(0.0f);
  const glm::vec4 coatLtc = coat && s.ltcAreaLights ? ltcTableLookup(p.clearcoatRoughness, coatNoV)
                                                    : glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  const float below = belowCoat(p, view);
  const glm::vec4 ltc =
      s.ltcAreaLights ? ltcTableLookup(lobeRoughness, std::max(glm::dot(p.normal, view), 1e-4f))
                      : glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  const bool sheen = p.sheenColor != glm::vec3(0.0f) &&
                     (o.only == ShadingTerms::Both || o.only == ShadingTerms::Sheen);
  const float sheenAlpha =
      shared::alphaFromRoughness(std::max(p.sheenRoughness, kMinSheenRoughness));
  glm::vec3 sum(0.0f);
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& light = lights[i];
    const glm::vec3 visible = i < visibility.size() ? visibility[i] : glm::vec3(1.0f);
    if (visible == glm::vec3(0.0f)) continue;
    const shared::ShadingLight sl = shadingLightOf(light);
    const shared::LightIncidence inc =
        shared::lightIncidence(sl, position, p.normal, view, lobeRoughness, s, ltc);
    const float profile =
        light.ies ? light.intensityToward(glm::normalize(position - light.position)) : 1.0f;
    glm::vec3 radiance(0.0f);
    if (o.only != ShadingTerms::Sheen)
      radiance += belowScale * shared::lightRadiance(m, p.normal, view, inc, dfg, s);
    // KHR_materials_transmission: the light from behind the surface, through it.
    if (o.only != ShadingTerms::Sheen && m.transmission > 0.0f)
      radiance +=
          belowScale * shared::transmittedLightRadiance(
                           m, p.normal, view,
                           shared::lightIncidence(shared::mirroredLight(sl, position, p.normal),
                                                  position, p.normal, view, lobeRoughness, s, ltc),
                           dfg, s);
    if (sheen)
      radiance += shared::sheenLightRadiance(p.sheenColor, sheenAlpha, s.sheenVisibility, p.normal,
                                             view, inc);
    radiance *= below;
    if (coat)
      radiance += shared::clearcoatLightRadiance(
          m, view,
          shared::lightIncidence(sl, position, p.clearcoatNormal, view, p.clearcoatRoughness, s,
                                 coatLtc),
          coatDfg, s);
    sum += sl.color * profile * visible * radiance;
  }
  return sum;
}

namespace {

// Specular antialiasing of the split sum's sample at `pixel`, whose ray met `hit`: the shading
// normals (and the coat's) of the rays one pixel over in x and in y, met on the same surface
// extended, whatever the samples per pixel. The other pixel is the one the viewer's shader
// differences, its partner in the 2 x 2 quad (dFdxFine, dFdyFine): right of an even column, left
// of an odd one, and alike down the rows.
void antialiasSpecular(SurfacePoint& p, const Scene& scene, const RayTracer& tracer,
                       const RayTracer::Hit& hit, const RayGenerator& generateRay,
                       glm::vec2 pixel) {
  const auto partner = [](float c) {
    return static_cast<int>(std::floor(c)) % 2 == 0 ? 1.0f : -1.0f;
  };
  // The neighbor's shading normals on this point's side (surfaceAt turns them to the neighbor's
  // ray, which at a silhouette may see the other side). Where that ray runs (nearly) along the
  // plane, its barycentrics would be non-finite or far out (and so would the texture
  // coordinates): the normal is taken as turned right over, the widest kernel, as the viewer's
  // derivatives there give it.
  const auto neighbor = [&](glm::vec2 step) {
    const Ray ray = generateRay(pixel + step);
    const RayTracer::Hit h = hitOnSameSurface(scene, tracer, hit, ray);
    if (!(std::isfinite(h.t) && std::abs(h.u) < 1e3f && std::abs(h.v) < 1e3f)) {
      SurfacePoint over = p;
      over.normal = -p.normal;
      over.clearcoatNormal = -p.clearcoatNormal;
      return over;
    }
    SurfacePoint q = surfaceAt(scene, tracer, h, ray);
    if (glm::dot(q.normal, p.normal) < 0.0f) q.normal = -q.normal;
    if (glm::dot(q.clearcoatNormal, p.clearcoatNormal) < 0.0f)
      q.clearcoatNormal = -q.clearcoatNormal;
    return q;
  };
  const SurfacePoint px = neighbor({partner(pixel.x), 0.0f});
  const SurfacePoint py = neighbor({0.0f, partner(pixel.y)});
  p.roughness = shared::specularAntialiasedRoughness(p.roughness, p.normalMapAlpha2,
                                                     px.normal - p.normal, py.normal - p.normal);
  if (p.clearcoat > 0.0f)
    p.clearcoatRoughness = shared::specularAntialiasedRoughness(
        p.clearcoatRoughness, p.clearcoatNormalMapAlpha2, px.clearcoatNormal - p.clearcoatNormal,
        py.clearcoatNormal - p.clearcoatNormal);
}

}  // namespace

void checkSheenVisibility(SheenVisibility table, const RenderOptions& o) {
  if (o.mode == RenderMode::SplitSum && table != o.sheenVisibility)
    fail("render", fmt::format("the sheen lobe's visibility is {}, but the bake's sheen table "
                               "(sheen_dfg) was integrated with {}",
                               sheenVisibilityName(o.sheenVisibility), sheenVisibilityName(table)));
}

std::uint64_t renderMemoryBytes(int width, int height) {
  // Measured: 52 bytes per pixel at 2048^2, 50 at 4096^2, and 40 MB besides; the screen-space
  // occlusion's view buffers and result add 40 bytes per pixel while it is computed, the
  // reflections' lit frame, view buffers and result 56, the transmission's opaque frame and its
  // chain (a vec4 per texel, 4 / 3 of the pixels) 24.
  return static_cast<std::uint64_t>(60e6 + 176.0 * width * height);
}

RenderResult renderScene(const Scene& scene, const Camera& camera, const BakeResult& bake,
                         const BakeOptions& bakeOptions, const RenderOptions& o,
                         const std::function<void(float)>& progress) {
  checkCamera(camera);
  if (o.mode == RenderMode::SplitSum && o.realTimeShadows == ShadowMode::Map && !o.shadowMaps &&
      !scene.lights.empty() && sceneCastsShadows(scene)) {
    // The sun's cascades are fitted to this camera's view.
    const ShadowMapBuilder builder(scene);
    const ShadowMaps maps = builder.build(scene.lights, &camera, o.shadowSettings);
    RenderOptions withMaps = o;
    withMaps.shadowMaps = &maps;
    return renderScene(scene, camera, bake, bakeOptions, withMaps, progress);
  }
  if (o.mode == RenderMode::SplitSum && o.screenAmbientOcclusion.enabled && !o.screenOcclusion) {
    // From the camera's view of the scene, as a rasterizer's depth and normal buffers hold it.
    const auto [lo, hi] = scene.bounds();
    const ScreenOcclusion occlusion = screenSpaceAmbientOcclusion(
        renderViewBuffers(scene, camera), camera,
        ambientOcclusionParameters(occlusionUnderVolume(o.screenAmbientOcclusion, o.volume),
                                   glm::length(hi - lo)));
    RenderOptions withOcclusion = o;
    withOcclusion.screenOcclusion = &occlusion;
    return renderScene(scene, camera, bake, bakeOptions, withOcclusion, progress);
  }
  if (o.mode == RenderMode::SplitSum && !o.transmissionFrame && o.cameraSeesTransmissive &&
      o.only != ShadingTerms::Diffuse && o.only != ShadingTerms::Sheen && hasTransmission(scene)) {
    // KHR_materials_transmission: the opaque surfaces' frame first, the transmissive ones read
    // it (the glTF Sample Viewer's order). It is lit as the frame of screen-space reflections is
    // (no area light in front of a surface), without the screen's occlusion, whose view buffers
    // hold the transmissive surfaces, and over a background of zero (the environment fills what
    // it leaves uncovered).
    RenderOptions opaque = o;
    opaque.cameraSeesTransmissive = false;
    opaque.cameraSeesEmitters = false;
    opaque.screenOcclusion = nullptr;
    opaque.screenReflection = nullptr;
    opaque.backgroundEnvironment = false;
    opaque.backgroundColor = glm::vec3(0.0f);
    // The render itself is let go once its chain is made.
    const TransmissionFrame frame = [&] {
      const RenderResult behind = renderRays(
          scene, camera.width, camera.height,
          [&](glm::vec2 pixel) { return camera.generateRay(pixel.x, pixel.y); }, bake, bakeOptions,
          opaque,
          [&](float f) {
            if (progress) progress(0.3f * f);
          });
      return transmissionFrameOf(behind.color, behind.alpha, camera);
    }();
    RenderOptions withFrame = o;
    withFrame.transmissionFrame = &frame;
    return renderScene(scene, camera, bake, bakeOptions, withFrame, [&](float f) {
      if (progress) progress(0.3f + 0.7f * f);
    });
  }
  if (o.mode == RenderMode::SplitSum && o.screenReflections.enabled && !o.screenReflection &&
      o.only != ShadingTerms::Diffuse && o.only != ShadingTerms::Sheen) {
    // The lit frame whose radiance the reflections' hits take (each surface's emission once),
    // then the frame with them.
    RenderOptions lit = o;
    lit.screenReflections.enabled = false;
    // The surfaces, not the area lights in front of them: the view buffers hold the surfaces, and
    // a light's reflection is its own shading's.
    lit.cameraSeesEmitters = false;
    const RenderResult first = renderScene(scene, camera, bake, bakeOptions, lit, [&](float f) {
      if (progress) progress(0.5f * f);
    });
    const auto [lo, hi] = scene.bounds();
    const ScreenReflections reflections =
        screenSpaceReflections(renderViewBuffers(scene, camera), first.color, camera,
                               reflectionParameters(o.screenReflections, glm::length(hi - lo)));
    RenderOptions withReflections = o;
    withReflections.screenReflection = &reflections;
    return renderScene(scene, camera, bake, bakeOptions, withReflections, [&](float f) {
      if (progress) progress(0.5f + 0.5f * f);
    });
  }
  return renderRays(
      scene, camera.width, camera.height,
      [&](glm::vec2 pixel) { return camera.generateRay(pixel.x, pixel.y); }, bake, bakeOptions, o,
      progress);
}

RenderResult renderRays(const Scene& scene, int width, int height, const RayGenerator& generateRay,
                        const BakeResult& bake, const BakeOptions& bakeOptions,
                        const RenderOptions& o, const std::function<void(float)>& progress) {
  if (width < 1 || height < 1)
    fail("render", fmt::format("an image of {} x {} pixels is empty", width, height));
  if (bake.sheenDfg)
    for (const Material& m : scene.materials)
      if (m.sheenColor != glm::vec3(0.0f)) checkSheenVisibility(bakeOptions.sheenVisibility, o);
  const auto start = std::chrono::steady_clock::now();
  const RayTracer tracer(scene);
  const EnvironmentSampler env(bake.source.levels[0]);
  if (o.mode == RenderMode::Reference) preparePathTracer();
  const EmissiveTriangles emitters(scene, tracer);
  const PathTracerScene pathScene{scene, tracer, env, o, emitters};
  const auto [lo, hi] = scene.bounds();
  // The lights' shadows in the split sum: maps (built here over the whole scene unless given),
  // or rays.
  const bool shadowed = o.mode == RenderMode::SplitSum && o.realTimeShadows != ShadowMode::None &&
                        !scene.lights.empty() && sceneCastsShadows(scene);
  ShadowMaps ownMaps;
  const ShadowMaps* maps = o.shadowMaps;
  if (shadowed && o.realTimeShadows == ShadowMode::Map && !maps) {
    ownMaps = buildShadowMaps(scene, tracer, {lo, hi}, scene.lights, nullptr, o.shadowSettings);
    maps = &ownMaps;
  }
  const ScreenOcclusion* screen = o.mode == RenderMode::SplitSum ? o.screenOcclusion : nullptr;
  const ScreenReflections* reflections =
      o.mode == RenderMode::SplitSum ? o.screenReflection : nullptr;
  if (reflections && (reflections->width != width || reflections->height != height))
    fail("render", fmt::format("the screen-space reflections are of {} x {} pixels, the image "
                               "{} x {}",
                               reflections->width, reflections->height, width, height));
  if (screen && (screen->width != width || screen->height != height))
    fail("render", fmt::format("the screen-space occlusion is of {} x {} pixels, the image {} x {}",
                               screen->width, screen->height, width, height));
  if (maps && maps->casters.size() != scene.lights.size())
    fail("render", fmt::format("the shadow maps are of {} lights, the scene has {}",
                               maps->casters.size(), scene.lights.size()));
  const float aoDistance = o.aoDistance > 0.0f ? o.aoDistance : 0.1f * glm::length(hi - lo);
  RenderResult result;
  result.color = Image(width, height);
  result.alpha.assign(static_cast<std::size_t>(width) * height, 0.0f);
  std::atomic<int> rowsDone{0};
  std::atomic<std::uint64_t> samples{0};
  const int spp = std::max(1, o.spp);
  const shared::ShadowMapView shadowView = maps ? maps->view() : shared::ShadowMapView{};
  parallelFor(0, height, [&](int y) {
    std::uint64_t rowSamples = 0;
    std::vector<glm::vec3> visibility(shadowed ? scene.lights.size() : 0);  // per light, reused
    for (int x = 0; x < width; ++x) {
      Sampler sampler(o.seed, static_cast<std::uint64_t>(y) * width + x);
      glm::dvec3 sum(0.0);
      double lumSum = 0.0, lumSq = 0.0;
      int covered = 0, taken = 0;
      for (int s = 0; s < spp; ++s) {
        // Every number of the sample from the pixel's low-discrepancy sampler, the position in
        // the pixel first: any prefix is spread over the pixel (for early stops and any spp);
        // one sample is the pixel center.
        sampler.startSample(static_cast<std::uint32_t>(s));
        const glm::vec2 j = spp == 1 ? glm::vec2(0.5f) : sampler.uniform2();
        const float jx = j.x, jy = j.y;
        const Ray ray = generateRay({static_cast<float>(x) + jx, static_cast<float>(y) + jy});
        const RayTracer::Hit hit =
            o.cameraSeesTransmissive ? tracer.intersect(ray) : firstOpaqueHit(tracer, ray);
        const NearestLight seen = o.cameraSeesEmitters
                                      ? nearestLight(scene.lights, ray.origin, ray.direction)
                                      : NearestLight{};
        glm::vec3 c;
        if (seen.index >= 0 && (!hit.found || seen.hit.distance < hit.t)) {
          if (std::isfinite(seen.hit.distance))
            ++covered;  // an emitter is a surface; the sun is not
          c = seen.hit.radiance;
        } else if (!hit.found) {
          c = o.backgroundEnvironment ? sampleBilinear(bake.source, 0, ray.direction)
                                      : o.backgroundColor;
        } else {
          ++covered;
          SurfacePoint p = surfaceAt(scene, tracer, hit, ray);
          const glm::vec3 position = p.position;
          if (o.mode == RenderMode::SplitSum) {
            if (o.specularAntialiasing)
              antialiasSpecular(p, scene, tracer, hit, generateRay,
                                {static_cast<float>(x) + jx, static_cast<float>(y) + jy});
            if (o.aoRays > 0 && !p.occlusionTexture)
              p.occlusion = ambientOcclusion(tracer, p, o.aoRays, aoDistance, sampler);
            if (screen) {
              // Lagarde & de Rousiers 2014, 4.10.3: the smaller of the material's and the screen's.
              const std::size_t i = static_cast<std::size_t>(y) * width + x;
              p.occlusion = std::min(p.occlusion, screen->visibility[i]);
              // The pixel's bent normal, unless it is another surface's (an edge sample).
              if (glm::dot(screen->bentNormals[i], p.normal) > 0.0f)
                p.bentNormal = screen->bentNormals[i];
            }
            if (reflections)
              p.screenReflection = reflections->reflection[static_cast<std::size_t>(y) * width + x];
            c = shadeSplitSum(p, -ray.direction, bake, bakeOptions, o);
            if (!scene.lights.empty()) {
              // The layer below the sheen is scaled as for the environment.
              const float NoV = std::max(glm::dot(p.normal, -ray.direction), 1e-4f);
              const float scaling =
                  p.sheenColor == glm::vec3(0.0f) || !bake.sheenDfg
                      ? 1.0f
                      : shared::sheenAlbedoScaling(
                            p.sheenColor,
                            sampleDfgLut(*bake.sheenDfg, NoV,
                                         std::max(p.sheenRoughness, kMinSheenRoughness))
                                .x);
              if (shadowed) {
                // A surface that transmits leaves its own crossing out of the maps' filters.
                const shared::SplitSumMaterial receiver = splitSumMaterial(p, 1.0f);
                for (std::size_t i = 0; i < scene.lights.size(); ++i)
                  visibility[i] =
                      o.realTimeShadows == ShadowMode::Ray
                          ? rayTracedVisibility(scene, tracer, scene.lights[i], position, p.normal,
                                                o.shadowSettings.raySamples, sampler)
                          : shared::shadowVisibility(
                                shadowView, maps->casters[i], position, p.normal,
                                shared::shadowReceiverCrossing(
                                    receiver, p.normal,
                                    shared::directionToLight(shadingLightOf(scene.lights[i]),
                                                             position)));
              }
              c += shadeLightsRealTime(p, position, -ray.direction, scene.lights, bake.dfg, o,
                                       scaling, visibility);
            }
          } else {
            c = tracePath(pathScene, p, position, -ray.direction, sampler);
          }
        }
        sum += glm::dvec3(c);
        ++taken;
        const double l = luminance(c);
        lumSum += l;
        lumSq += l * l;
        // Progressive: stop once the pixel's relative standard error is below the threshold.
        if (o.noiseThreshold > 0.0f && taken >= 16 && taken % 8 == 0) {
          const double mean = lumSum / taken;
          const double variance = std::max(0.0, lumSq / taken - mean * mean);
          if (std::sqrt(variance / taken) <= o.noiseThreshold * std::max(mean, 1e-6)) break;
        }
      }
      result.color.at(x, y) = glm::vec3(sum / static_cast<double>(taken));
      result.alpha[static_cast<std::size_t>(y) * width + x] =
          static_cast<float>(covered) / static_cast<float>(taken);
      rowSamples += static_cast<std::uint64_t>(taken);
    }
    samples += rowSamples;
    const int done = ++rowsDone;
    if (progress && done % 16 == 0) progress(static_cast<float>(done) / static_cast<float>(height));
  });
  result.samples = static_cast<double>(samples.load());
  result.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace ibl