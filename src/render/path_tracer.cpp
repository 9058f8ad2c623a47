#include "path_tracer.hpp"

#include <numbers>
#include <optional>

#include "ibl/bake/dfg.hpp"
#include "ibl/bake/prefilter.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/math/brdf.hpp"
#include "ibl/math/sampling.hpp"
#include "ibl/shared/material.h"
#include "ibl/shared/path_brdf.h"
#include "ibl/shared/split_sum.h"
#include "ibl/shared/transmission.h"

namespace ibl {

namespace {

// E(n.v, r) = A + B, the share of a white furnace that a single-scattering GGX lobe with F0 = 1
// reflects, bilinear between nodes that include the edges n.v = 0, 1 and r = 0, 1 (a DFG
// table's texel centers stop half a texel short, 3 % off at r = 1): the reference's material
// must not inherit the split sum's table error. Integrated once per process (~1M evaluations).
constexpr int kNodes = 33;

const std::vector<float>& directionalAlbedoTable() {
  static const std::vector<float> table = [] {
    std::vector<float> t(kNodes * kNodes);
    parallelFor(0, kNodes, [&](int j) {
      for (int i = 0; i < kNodes; ++i) {
        const glm::vec3 e = integrateDfg(std::max(static_cast<float>(i) / (kNodes - 1), 1e-3f),
                                         static_cast<float>(j) / (kNodes - 1), 1024);
        t[static_cast<std::size_t>(j) * kNodes + i] = e.x + e.y;
      }
    });
    return t;
  }();
  return table;
}

// E(n.v, r) of the sheen lobe (D_charlie V, V the chosen visibility), bilinear in a table
// integrated once per process and visibility like the one above (integrateSheenDfg: 33^2 nodes
// of 1024 points, the edges included).
std::vector<float> sheenAlbedoNodes(SheenVisibility visibility) {
  std::vector<float> t(kNodes * kNodes);
  parallelFor(0, kNodes, [&](int j) {
    for (int i = 0; i < kNodes; ++i)
      t[static_cast<std::size_t>(j) * kNodes + i] = integrateSheenDfg(
          std::max(static_cast<float>(i) / (kNodes - 1), 1e-3f),
          std::max(static_cast<float>(j) / (kNodes - 1), 1e-3f), 1024, visibility);
  });
  return t;
}
const std::vector<float>& sheenAlbedoTable(SheenVisibility visibility) {
  static const std::vector<float> charlie = sheenAlbedoNodes(SheenVisibility::Charlie);
  if (visibility == SheenVisibility::Charlie) return charlie;
  static const std::vector<float> neubelt = sheenAlbedoNodes(SheenVisibility::Neubelt);
  return neubelt;
}

float maxComponent(glm::vec3 c) {
  return std::max(c.x, std::max(c.y, c.z));
}

// The Fresnel reflectance of the material at p (KHR_materials_ior, _specular and _iridescence).
shared::SpecularReflectance reflectanceOf(const SurfacePoint& p, bool microOcclusion) {
  return shared::withIridescence(
      shared::specularReflectance(p.baseColor, p.metallic, p.ior, p.specular, p.specularColor,
                                  microOcclusion),
      p.iridescence, p.iridescenceIor, p.iridescenceThickness);
}

// The index of refraction below the surface at p over the side the ray came from
// (shared::withTransmission's eta): the material's ior entering its volume, its inverse leaving
// it; 0 for a thin wall (no volume, or KHR_materials_ior's infinite index 0).
float transmissionEta(const SurfacePoint& p) {
  return p.volume ? shared::volumeRelativeIndex(p.ior, p.frontFace) : 0.0f;
}

// The material at one point (ibl/shared/path_brdf.h, which the GPU reference evaluates too).
struct Brdf {
  shared::PathBrdf b;
  shared::AlbedoTables tables;

  // The material at p seen from local direction v, its coat's normal `coatNormal` and its
  // anisotropy's direction `anisotropyTangent` (both local); `lobes` (shared::kLobes...)
  // selects lobes.
  static Brdf of(const SurfacePoint& p, glm::vec3 v, glm::vec3 coatNormal,
                 glm::vec3 anisotropyTangent, int lobes, const RenderOptions& o) {
    const shared::AlbedoTables tables = referenceAlbedoTables(o.sheenVisibility);
    shared::PathBrdf b = shared::pathBrdfOf(
        tables, p.baseColor, p.metallic, p.roughness, reflectanceOf(p, o.specularMicroOcclusion),
        p.sheenColor, p.sheenRoughness, v, lobes, pathShading(o));
    if (p.clearcoat > 0.0f)
      b = shared::withClearcoat(b, p.clearcoat, p.clearcoatRoughness, coatNormal, v);
    if (p.anisotropy > 0.0f)
      b = shared::withAnisotropy(tables, b, p.anisotropy, anisotropyTangent, v, pathShading(o));
    if (p.transmission > 0.0f)
      b = shared::withTransmission(tables, b, p.transmission, p.baseColor, p.metallic,
                                   transmissionEta(p), v);
    return {b, tables};
  }
  // f(v, l) (n.l), with n = +Z of the local frame (with the walk, an unbiased estimate drawn
  // from a branch of the sampler, which it does not advance).
  glm::vec3 evaluate(glm::vec3 v, glm::vec3 l, const Sampler& sampler) const {
    return shared::evaluatePathBrdf(tables, b, v, l, sampler, true);
  }
  float pdf(glm::vec3 v, glm::vec3 l) const { return shared::pathBrdfPdf(b, v, l); }
  shared::PathBrdfSample sample(glm::vec3 v, Sampler& sampler) const {
    return shared::samplePathBrdf(tables, b, v, sampler);
  }
};

using shared::powerHeuristic;

}  // namespace

shared::AlbedoTables referenceAlbedoTables(SheenVisibility visibility) {
  return {directionalAlbedoTable().data(), sheenAlbedoTable(visibility).data()};
}

shared::PathShading pathShading(const RenderOptions& o) {
  shared::PathShading s;
  s.diffuseModel = o.diffuse == DiffuseModel::Disney ? 0 : 1;
  s.multipleScattering = static_cast<int>(o.multipleScattering);
  s.specularMicroOcclusion = o.specularMicroOcclusion;
  s.sheenVisibility = static_cast<int>(o.sheenVisibility);
  return s;
}

NearestLight nearestLight(const std::vector<Light>& lights, glm::vec3 p, glm::vec3 w) {
  NearestLight best;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const std::optional<LightHit> h = intersectLight(lights[i], p, w);
    if (h && (best.index < 0 || h->distance < best.hit.distance)) {
      best.index = static_cast<int>(i);
      best.hit = *h;
    }
  }
  return best;
}

EnvironmentSampler::EnvironmentSampler(const std::array<Image, kFaceCount>& level)
    : level_(level), n_(level[0].width) {
  const std::size_t n = static_cast<std::size_t>(n_), rows = kFaceCount * n;
  double mean = 0.0;
  for (int f = 0; f < kFaceCount; ++f)
    for (const auto& p : level[f].pixels) mean += luminance(p);
  mean /= static_cast<double>(rows * n);
  const std::vector<double> omega = faceTexelSolidAngles(n_);
  rowCdf_.resize(rows);
  columnCdf_.resize(rows * n);
  double total = 0.0;
  for (std::size_t row = 0; row < rows; ++row) {
    const Image& face = level[row / n];
    const int y = static_cast<int>(row % n);
    double* column = columnCdf_.data() + row * n;
    double sum = 0.0;
    for (std::size_t x = 0; x < n; ++x) {
      // A floor keeps every texel reachable, for MIS and for colors of low luminance.
      sum += (luminance(face.at(static_cast<int>(x), y)) + 1e-3 * mean + 1e-12) *
             omega[static_cast<std::size_t>(y) * n + x];
      column[x] = sum;
    }
    for (std::size_t x = 0; x < n; ++x) column[x] /= sum;
    column[n - 1] = 1.0;
    total += sum;
    rowCdf_[row] = total;
  }
  for (auto& c : rowCdf_) c /= total;
  rowCdf_.back() = 1.0;
  texelArea_ = 4.0f / static_cast<float>(n_ * n_);
}

void preparePathTracer() {
  directionalAlbedoTable();
}

// Lagarde & de Rousiers 2014, 4.9.1.2: a probe capture keeps the diffuse light of the surfaces it
// sees, so a metal (no diffuse lobe) would be black; it is seen as a diffuse surface whose albedo
// is its F0 instead. Its metallic share keeps all of that albedo: fresnel_mix's layer
// (diffuseWeight) is the dielectric share's alone.
SurfacePoint metalAsDiffuse(SurfacePoint p) {
  p.baseColor = shared::metalAsDiffuseColor(p.baseColor, p.metallic, reflectanceOf(p, false).f0);
  p.specular *= 1.0f - p.metallic;
  p.metallic = 0.0f;
  return p;
}

namespace {

// The material at p (a capture's metals as diffuse) as the path shades it, seen from local
// direction v in the frame toLocal: a capture's lobes while the path is seen by the probe.
Brdf vertexBrdf(const RenderOptions& o, SurfacePoint& p, const glm::mat3& toLocal, glm::vec3 v,
                bool seenByProbe) {
  const int lobes = seenByProbe ? shared::kLobesCapture : static_cast<int>(o.only);
  if (seenByProbe && o.captureMetalsAsDiffuse) p = metalAsDiffuse(p);
  return Brdf::of(p, v, toLocal * p.clearcoatNormal, toLocal * p.anisotropyTangent, lobes, o);
}

// What arrives at origin of the light that leaves origin + distance w toward it: nothing behind a
// surface the path would scatter on, and through those it crosses straight (smooth thin walls:
// shared::pathCrossesStraight) their transmittance, as the path that crosses them weighs it.
glm::vec3 shadowTransmittance(const PathTracerScene& s, glm::vec3 origin, glm::vec3 w,
                              float distance, bool seenByProbe) {
  const RayTracer& tracer = s.tracer;
  if (!tracer.transmits()) return glm::vec3(tracer.occluded(origin, w, distance) ? 0.0f : 1.0f);
  if (tracer.occluded(origin, w, distance, RayTracer::kOpaque)) return glm::vec3(0.0f);
  glm::vec3 passed(1.0f);
  crossTransmissive(
      tracer, {origin, w}, distance,
      [&](const RayTracer::Hit& hit, const Ray& segment, float) {
        if (passed == glm::vec3(0.0f)) return;
        SurfacePoint q = surfaceAt(s.scene, tracer, hit, segment);
        const glm::mat3 toLocal = glm::transpose(tangentFrame(q.normal));
        const glm::vec3 v = toLocal * -w;
        const Brdf brdf = vertexBrdf(s.options, q, toLocal, v, seenByProbe);
        passed *= shared::pathCrossesStraight(brdf.b)
                      ? shared::pathStraightTransmittance(brdf.tables, brdf.b, v)
                      : glm::vec3(0.0f);
      },
      CrossingEnd::Exact);
  return passed;
}

// The most surfaces one path crosses straight (crossTransmissive's bound); past them it ends.
constexpr int kMaxCrossings = 256;

// Where the path last scattered: the density of its sample (0 for the camera's ray, which no
// other strategy samples) and the points it left from, for the MIS weight of a light the ray meets
// past the surfaces it crosses straight, and how far it has gone since.
struct Scattering {
  float pdf = 0.0f;
  glm::vec3 origin{0.0f}, position{0.0f};
  float travelled = 0.0f;

  // The weight of what the ray meets against the strategy of density `other` that samples it
  // from `origin`.
  float weight(float other) const { return pdf > 0.0f ? powerHeuristic(pdf, other) : 1.0f; }
};

}  // namespace

glm::vec3 tracePath(const PathTracerScene& s, SurfacePoint p, glm::vec3 position, glm::vec3 view,
                    Sampler& sampler) {
  const RenderOptions& o = s.options;
  const std::vector<Light>& lights = s.scene.lights;
  // Beyond direct light the path needs to know what the scene hides; --shadows asks for it
  // with direct light alone.
  const bool visibility = o.shadows || o.bounces > 0;
  glm::vec3 sum(0.0f), throughput(1.0f);
  // The attenuation coefficient of the volume the path travels in (KHR_materials_volume; 0:
  // none), and the share of light that crosses `distance` of it.
  glm::vec3 medium(0.0f);
  // A probe capture (Lagarde & de Rousiers 2014, 4.9.1.2) keeps the diffuse of the surfaces it
  // sees and the light they let through, but not their view-dependent reflections: the surfaces
  // seen through glass are seen by the probe too.
  bool seenByProbe = !o.cameraSeesSpecular;
  const auto crossing = [&](const glm::vec3& sigma, float distance) {
    return sigma == glm::vec3(0.0f) ? glm::vec3(1.0f)
                                    : shared::volumeTransmittance(sigma, distance);
  };
  // The camera's ray first: what it meets through surfaces crossed straight is seen as it is.
  Scattering last{0.0f, position, position, 0.0f};
  // Bounces count scatterings: a surface crossed straight is none. Past the last one the path
  // goes on only through such surfaces, to meet the lights a shadow ray through them reached.
  int bounce = 0, crossings = 0;
  bool pastLastBounce = false;
  // The emission of the first surface; further ones are counted where the BRDF's sample meets
  // them, weighed against the emitters' sampling.
  sum += p.emissive;
  for (;;) {
    const glm::mat3 frame = tangentFrame(p.normal);
    const glm::mat3 toLocal = glm::transpose(frame);
    const glm::vec3 v = toLocal * view;
    Brdf brdf = vertexBrdf(o, p, toLocal, v, seenByProbe);
    const glm::vec3 offset = p.normal * 1e-4f * std::max(1.0f, glm::length(position));
    // A smooth thin wall is crossed (its transmission's share, with the probability of choosing
    // its transmission) or met (its other lobes).
    bool straight = false;
    // A surface that transmits (met or crossed) is left by the side of its own plane (below).
    const bool sidedByPlane = shared::pathTransmissionLobe(brdf.b);
    if (shared::pathCrossesStraight(brdf.b)) {
      if (++crossings > kMaxCrossings) break;
      const float chance = pastLastBounce ? 1.0f : shared::pathTransmissionProbability(brdf.b, v);
      straight = pastLastBounce || sampler.uniform() < chance;
      if (straight)
        throughput *= shared::pathStraightTransmittance(brdf.tables, brdf.b, v) / chance;
      else
        throughput /= 1.0f - chance;
      brdf.b = shared::withoutTransmission(brdf.b);
    }
    if (pastLastBounce && !straight) break;
    const glm::vec3 origin = position + offset;
    // A surface that transmits is lit and left on both sides (local l.z < 0 too). The side of
    // its own plane a direction goes to (faceNormal's, where a shading normal may lean past the
    // ray) is where it leaves from, and whether it goes on inside the volume (a thin wall keeps
    // the medium).
    const bool twoSided = shared::pathTransmissionLobe(brdf.b);
    const auto leaves = [&](glm::vec3 l) { return l.z > 0.0f || (twoSided && l.z < 0.0f); };
    const auto inward = [&](glm::vec3 l) { return glm::dot(frame * l, p.faceNormal) < 0.0f; };
    const auto originToward = [&](glm::vec3 l) {
      if (!sidedByPlane) return origin;
      return position + p.faceNormal * (inward(l) ? -1.0f : 1.0f) * glm::length(offset);
    };
    const auto mediumToward = [&](glm::vec3 l) {
      if (!twoSided || !p.volume) return medium;
      return inward(l) ? p.attenuation : glm::vec3(0.0f);
    };
    Ray ray;
    if (straight) {
      // On along the same direction, from the surface's far side.
      const float side = glm::dot(view, p.faceNormal) > 0.0f ? -1.0f : 1.0f;
      ray = {position + p.faceNormal * side * glm::length(offset), -view};
    } else {
      // What reaches the point from w (up to distance): the shadow ray's, and the medium's.
      const auto unoccluded = [&](glm::vec3 l, glm::vec3 w, float distance) {
        // Stop short of an area light's surface: the lights are not in the ray tracer.
        if (!visibility) return crossing(mediumToward(l), distance);
        return shadowTransmittance(s, originToward(l), w,
                                   std::isfinite(distance) ? distance * (1.0f - 1e-4f) : INFINITY,
                                   seenByProbe && l.z < 0.0f) *
               crossing(mediumToward(l), distance);
      };
      // A light's sample at local l (world w, up to distance) of `radiance` and MIS weight
      // `weight`: the BRDF evaluated only where the shadow ray lets something through.
      const auto addLight = [&](glm::vec3 l, glm::vec3 w, float distance, glm::vec3 radiance,
                                float weight) {
        const glm::vec3 passed = unoccluded(l, w, distance);
        if (passed != glm::vec3(0.0f))
          sum += throughput * brdf.evaluate(v, l, sampler) * radiance * weight * passed;
      };
      // Next-event estimation: one sample of each light (punctual lights exactly) and one of the
      // environment where no light hides it, each weighed against the BRDF's sampling.
      for (const Light& light : lights) {
        const LightSample ls = sampleLight(light, origin, sampler.uniform2());
        if (!(ls.delta || ls.pdf > 0.0f) || ls.radiance == glm::vec3(0.0f)) continue;
        const glm::vec3 l = toLocal * ls.direction;
        if (!leaves(l)) continue;
        const float weight = ls.delta ? 1.0f : powerHeuristic(ls.pdf, brdf.pdf(v, l)) / ls.pdf;
        addLight(l, ls.direction, ls.distance, ls.radiance, weight);
      }
      // One point on the emissive triangles (by power); without visibility the BRDF's samples
      // are not traced, so this sample takes all the weight. An analytic light in front hides
      // it, as it stops the BRDF's samples.
      if (!s.emitters.empty()) {
        // In this order on every compiler: the draws' order is their dimensions'.
        const float pick = sampler.uniform();
        const glm::vec2 point = sampler.uniform2();
        const EmitterSample es = s.emitters.sample(origin, glm::vec3(pick, point));
        const glm::vec3 l = toLocal * es.direction;
        const auto lightInFront = [&] {
          const NearestLight nl = nearestLight(lights, origin, es.direction);
          return nl.index >= 0 && nl.hit.distance < es.distance;
        };
        if (es.pdf > 0.0f && es.radiance != glm::vec3(0.0f) && leaves(l) && !lightInFront()) {
          const float weight =
              visibility ? powerHeuristic(es.pdf, brdf.pdf(v, l)) / es.pdf : 1.0f / es.pdf;
          addLight(l, es.direction, es.distance, es.radiance, weight);
        }
      }
      if (o.environmentLight) {
        const glm::vec3 w = s.environment.sample(sampler.uniform2());
        const glm::vec3 l = toLocal * w;
        const float pe = s.environment.pdf(w);
        if (leaves(l) && pe > 0.0f && nearestLight(lights, origin, w).index < 0)
          addLight(l, w, INFINITY, s.environment.radiance(w),
                   powerHeuristic(pe, brdf.pdf(v, l)) / pe);
      }
      // The BRDF's sample: it ends on a light or the environment (weighed against their
      // sampling), or goes on from the surface it meets.
      const shared::PathBrdfSample bs = brdf.sample(v, sampler);
      const glm::vec3 l = bs.direction;
      const float pb = brdf.pdf(v, l);
      if (!(pb > 0.0f) || bs.weight == glm::vec3(0.0f)) break;
      // bs.weight is f cos / p of the sampled lobe (with the microfacet walk an estimate of it,
      // pb the MIS weights' approximate pdf; Brdf::sample).
      throughput *= bs.weight;
      medium = mediumToward(l);
      seenByProbe = seenByProbe && twoSided && l.z < 0.0f;  // through the surface: still in view
      ray = {originToward(l), frame * l};
      last = {pb, ray.origin, position, 0.0f};
    }
    const glm::vec3 w = ray.direction;
    // The camera's ray through a window is seen as the camera sees: what lies behind (without
    // visibility too), the lights where it sees them, without their range's window.
    const bool fromCamera = last.pdf == 0.0f;
    const RayTracer::Hit hit =
        visibility || fromCamera ? s.tracer.intersect(ray) : RayTracer::Hit{};
    const NearestLight seen =
        !fromCamera || o.cameraSeesEmitters ? nearestLight(lights, ray.origin, w) : NearestLight{};
    if (seen.index >= 0 && (!hit.found || seen.hit.distance < hit.t)) {
      const Light& light = lights[static_cast<std::size_t>(seen.index)];
      sum += throughput * seen.hit.radiance *
             (fromCamera ? 1.0f : lightWindow(light, last.position)) *
             last.weight(lightPdf(light, last.origin, w)) * crossing(medium, seen.hit.distance);
      break;
    }
    if (!hit.found) {
      if (o.environmentLight)
        sum += throughput * s.environment.radiance(w) * last.weight(s.environment.pdf(w)) *
               crossing(medium, INFINITY);
      break;
    }
    throughput *= crossing(medium, hit.t);
    last.travelled += hit.t;
    // An emissive surface met: its emission, weighed against the sampling of the emitters.
    const bool sphere = s.tracer.isSphere(hit.geometry);
    const Material& met = hitMaterial(s.scene, s.tracer, hit);
    std::optional<SurfacePoint> next;
    if (met.emissive != glm::vec3(0.0f)) {
      next = surfaceAt(s.scene, s.tracer, hit, ray);
      const float pe =
          sphere ? 0.0f : s.emitters.pdf(w, last.travelled, hit.geometry, hit.primitive);
      sum += throughput * next->emissive * last.weight(pe);
    }
    if (!straight) {
      if (bounce >= o.bounces) {
        // Only a surface that may be crossed straight is worth going on to.
        if (met.transmission <= 0.0f) break;
        pastLastBounce = true;
      } else if (bounce >= 1) {
        // Russian roulette after two bounces: go on with the probability of the throughput.
        const float q = std::min(maxComponent(throughput), 0.95f);
        if (!(sampler.uniform() < q)) break;
        throughput /= q;
      }
      ++bounce;
    }
    p = next ? *next : surfaceAt(s.scene, s.tracer, hit, ray);
    position = ray.origin + hit.t * ray.direction;
    view = -w;
  }
  return sum;
}

}  // namespace ibl
