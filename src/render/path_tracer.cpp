#include "path_tracer.hpp"

#include <numbers>
#include <optional>

#include "ibl/bake/dfg.hpp"
#include "ibl/bake/prefilter.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/math/brdf.hpp"
#include "ibl/math/sampling.hpp"
#include "ibl/shared/split_sum.h"
#include "microfacet_walk.hpp"

namespace ibl {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kMinAlpha = 1e-3f;  // GGX of alpha 0 is a delta; 1e-3 is a mirror in practice

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

// Bilinear in one of the tables above at (n.v, r).
float tableLookup(const std::vector<float>& table, float NoV, float roughness) {
  const float x = std::clamp(NoV, 0.0f, 1.0f) * (kNodes - 1);
  const float y = std::clamp(roughness, 0.0f, 1.0f) * (kNodes - 1);
  const int i = std::min(static_cast<int>(x), kNodes - 2),
            j = std::min(static_cast<int>(y), kNodes - 2);
  const float fx = x - static_cast<float>(i), fy = y - static_cast<float>(j);
  const auto at = [&](int a, int b) { return table[static_cast<std::size_t>(b) * kNodes + a]; };
  return glm::mix(glm::mix(at(i, j), at(i + 1, j), fx),
                  glm::mix(at(i, j + 1), at(i + 1, j + 1), fx), fy);
}

float directionalAlbedo(float NoV, float roughness) {
  return tableLookup(directionalAlbedoTable(), NoV, roughness);
}

float maxComponent(glm::vec3 c) {
  return std::max(c.x, std::max(c.y, c.z));
}

// The material's BRDF pieces at one point.
struct Brdf {
  glm::vec3 diffuseColor, f0;
  float alpha, roughness;
  float f90;  // Schlick's grazing reflectance (RenderOptions::specularMicroOcclusion)
  DiffuseModel diffuseModel;
  ShadingTerms only;
  glm::vec3 multipleScattering;  // the specular lobe's scale for the bounces between microfacets
  // MultipleScattering::Walk: the specular lobe is Heitz et al. 2016's random walk on the
  // microsurface (microfacet_walk.hpp), its single scattering the analytic GGX term below.
  bool walk = false;
  MicrofacetWalk microsurface{1.0f, glm::vec3(1.0f), 1.0f};
  // KHR_materials_sheen: f = f_sheen + f_below min(1 - s E(n.v), 1 - s E(n.l)), s =
  // max(sheenColor), f_sheen = sheenColor D_charlie V (the specification's layering), V the
  // visibility of RenderOptions::sheenVisibility.
  glm::vec3 sheenColor{0.0f};
  float sheenRoughness = 0.0f, sheenAlpha = 1.0f, sheenScaleV = 1.0f;
  SheenVisibility sheenVisibility = SheenVisibility::Charlie;
  bool hasSheen() const { return sheenColor != glm::vec3(0.0f); }

  // The material at p seen from local direction v; `only` selects lobes.
  static Brdf of(const SurfacePoint& p, glm::vec3 v, ShadingTerms only, const RenderOptions& o) {
    Brdf b{p.baseColor * (1.0f - p.metallic),
           glm::mix(glm::vec3(0.04f), p.baseColor, p.metallic),
           std::max(alphaFromRoughness(p.roughness), kMinAlpha),
           p.roughness,
           1.0f,
           o.diffuse,
           only,
           glm::vec3(1.0f)};
    b.f90 = shared::fresnelF90(b.f0, o.specularMicroOcclusion);
    // The energy the single-scattering lobe loses to further bounces between microfacets,
    // returned by the split sum's own compensation (Fdez-Aguera 2019, as Filament does): the
    // lobe is scaled by 1 + F0 (1 / E(n.v) - 1). With F0 = 1 it
    // reflects everything (a white furnace); both render modes compute the same material.
    // MultipleScattering::Walk computes the bounces instead: nearly the same energy (within 5 %
    // for F0 = 0.9), in another shape (docs/render.md, "Multiple scattering in the reference").
    if (o.multipleScattering == MultipleScattering::Scale && only != ShadingTerms::Diffuse) {
      const float e = directionalAlbedo(std::max(v.z, 1e-4f), p.roughness);
      b.multipleScattering = shared::multipleScatteringCompensation(b.f0, glm::vec2(e, 0.0f));
    }
    if (o.multipleScattering == MultipleScattering::Walk && only != ShadingTerms::Diffuse) {
      b.walk = true;
      b.microsurface = MicrofacetWalk(b.alpha, b.f0, b.f90);
    }
    if (p.sheenColor != glm::vec3(0.0f)) {
      // The split sum's sheen prefilter stops at kMinSheenRoughness: the same material here.
      b.sheenColor = p.sheenColor;
      b.sheenVisibility = o.sheenVisibility;
      b.sheenRoughness = std::max(p.sheenRoughness, kMinSheenRoughness);
      b.sheenAlpha = alphaFromRoughness(b.sheenRoughness);
      b.sheenScaleV = b.albedoScaling(v.z);
    }
    return b;
  }

  bool specularLobe() const { return only == ShadingTerms::Both || only == ShadingTerms::Specular; }
  bool diffuseLobe() const { return only == ShadingTerms::Both || only == ShadingTerms::Diffuse; }
  bool sheenLobe() const {
    return hasSheen() && (only == ShadingTerms::Both || only == ShadingTerms::Sheen);
  }
  // 1 - max(sheenColor) E(c, sheen roughness).
  float albedoScaling(float c) const {
    return shared::sheenAlbedoScaling(sheenColor, tableLookup(sheenAlbedoTable(sheenVisibility),
                                                              std::max(c, 1e-4f), sheenRoughness));
  }

  // The view as the walk takes it: above the horizon (shading normals can put v below it; the
  // analytic terms clamp n.v to 1e-4 alike).
  static glm::vec3 walkView(glm::vec3 v) {
    return v.z >= 1e-4f ? v : glm::normalize(glm::vec3(v.x, v.y, 1e-4f));
  }

  // f(v, l) (n.l), with n = +Z of the local frame. With the walk, an unbiased estimate (sampler:
  // the walk's numbers; unused otherwise); withSpecular = false leaves the specular lobe out.
  glm::vec3 evaluate(glm::vec3 v, glm::vec3 l, Sampler& sampler, bool withSpecular = true) const {
    const float NoV = std::max(v.z, 1e-4f), NoL = l.z;
    if (NoL <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 h = glm::normalize(v + l);
    glm::vec3 result(0.0f);
    if (specularLobe() && withSpecular) {
      const float VoH = std::max(glm::dot(v, h), 0.0f);
      result += ggxDistribution(h.z, alpha) * smithGgxCorrelatedVisibility(NoV, NoL, alpha) *
                fresnelSchlick(f0, f90, VoH) * multipleScattering;
      // The walk's orders 2 and up (f cos, hence the division): its order 1 has the
      // expectation of the term above, which is exact.
      if (walk) {
        // The walk draws as many numbers as it takes bounces: from a stream of its own, so
        // that the path's later numbers keep their dimensions.
        Sampler walkNumbers = sampler.branch();
        result += microsurface.evaluate(walkView(v), l, walkNumbers, 2) / NoL;
      }
    }
    if (diffuseLobe()) {
      const float fd = diffuseModel == DiffuseModel::Disney
                           ? disneyDiffuseRenormalized(NoV, NoL, glm::dot(l, h), roughness)
                           : 1.0f;
      result += diffuseColor * (fd / kPi);
    }
    if (hasSheen()) {
      result *= std::min(sheenScaleV, albedoScaling(NoL));
      if (sheenLobe())
        result += sheenColor * (shared::charlieDistribution(h.z, sheenAlpha) *
                                ibl::sheenVisibility(sheenVisibility, NoV, NoL, sheenAlpha));
    }
    return result * NoL;
  }

  // Probability of sampling the sheen lobe (cosine-distributed: the Charlie lobe is broad).
  float sheenProbability() const {
    if (!sheenLobe()) return 0.0f;
    if (only == ShadingTerms::Sheen) return 1.0f;
    return std::clamp(0.5f * maxComponent(sheenColor), 0.1f, 0.5f);
  }

  // Probability of picking the specular lobe when sampling the layer below.
  float specularProbability() const {
    if (!specularLobe()) return 0.0f;
    if (!diffuseLobe()) return 1.0f;
    const float s = luminance(f0) + 0.04f, d = luminance(diffuseColor);
    if (d <= 0.0f) return 1.0f;  // a metal: no diffuse lobe to sample
    return std::clamp(s / (s + d), 0.1f, 0.9f);
  }

  float pdf(glm::vec3 v, glm::vec3 l) const {
    if (l.z <= 0.0f) return 0.0f;
    const float pSheen = sheenProbability();
    const float ps = specularProbability();
    float p = (1.0f - ps) * l.z / kPi;
    if (ps > 0.0f) {
      const glm::vec3 h = glm::normalize(v + l);
      const float NoV = std::max(v.z, 1e-4f);
      // Visible normals, reflected: pdf(l) = G1(v) D(h) / (4 n.v).
      p += ps * smithGgxMasking(NoV, alpha) * ggxDistribution(h.z, alpha) / (4.0f * NoV);
    }
    return pSheen * l.z / kPi + (1.0f - pSheen) * p;
  }

  // A direction l and its weight f(v, l) (n.l) / p(l).
  struct Sample {
    glm::vec3 direction;
    glm::vec3 weight;
  };
  Sample sample(glm::vec3 v, Sampler& sampler) const {
    const glm::vec2 xi = sampler.uniform2();
    float choose = sampler.uniform();
    const float pSheen = sheenProbability();
    if (walk) {
      // The walk's directions have no pdf to evaluate: one lobe is estimated at a time, the
      // specular by the walk's sample (weight: its f cos / p, the Fresnel of its bounces, times
      // the sheen layer's scaling) over the probability of choosing it, the others (sheen and
      // diffuse, both cosine-distributed) by f cos / p over the probability of the rest. Each
      // lobe's estimate is unbiased, so their sum is; pdf() (single scattering for the
      // specular) serves the MIS weights alone, as an approximation: the light's weight and
      // this sample's, computed from the same pdf() at the same l, still sum to 1, which is
      // all an unbiased MIS estimator needs (Veach 1997, section 9.2.2); a pdf away from the
      // walk's true one costs variance, not bias.
      const float specular = (1.0f - pSheen) * specularProbability();
      if (choose < specular) {
        Sampler walkNumbers = sampler.branch();  // as in evaluate()
        const MicrofacetWalk::Sample s = microsurface.sample(walkView(v), walkNumbers);
        glm::vec3 weight = s.weight / specular;
        if (hasSheen()) weight *= std::min(sheenScaleV, albedoScaling(s.wo.z));
        return {s.wo, weight};
      }
      const glm::vec3 l = sampleCosineHemisphere(xi);
      const float p = (1.0f - specular) * l.z / kPi;
      if (!(p > 0.0f)) return {l, glm::vec3(0.0f)};
      return {l, evaluate(v, l, sampler, false) / p};
    }
    glm::vec3 l;
    if (choose < pSheen) {
      l = sampleCosineHemisphere(xi);
    } else {
      choose = (choose - pSheen) / (1.0f - pSheen);
      if (choose < specularProbability()) {
        const glm::vec3 h = sampleGgxVisibleNormal(v, xi, alpha);
        l = 2.0f * glm::dot(v, h) * h - v;
      } else {
        l = sampleCosineHemisphere(xi);
      }
    }
    const float p = pdf(v, l);
    if (!(p > 0.0f)) return {l, glm::vec3(0.0f)};
    return {l, evaluate(v, l, sampler) / p};
  }
};

float powerHeuristic(float a, float b) {
  return a * a / (a * a + b * b);
}

}  // namespace

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
// is its F0 instead.
static SurfacePoint metalAsDiffuse(SurfacePoint p) {
  const glm::vec3 f0 = glm::mix(glm::vec3(0.04f), p.baseColor, p.metallic);
  p.baseColor = p.baseColor * (1.0f - p.metallic) + p.metallic * f0;
  p.metallic = 0.0f;
  return p;
}

glm::vec3 tracePath(const PathTracerScene& s, SurfacePoint p, glm::vec3 position, glm::vec3 view,
                    Sampler& sampler) {
  const RenderOptions& o = s.options;
  const std::vector<Light>& lights = s.scene.lights;
  // Beyond direct light the path needs to know what the scene hides; --shadows asks for it
  // with direct light alone.
  const bool visibility = o.shadows || o.bounces > 0;
  glm::vec3 sum(0.0f), throughput(1.0f);
  for (int depth = 0;; ++depth) {
    // The emission of the first surface; further ones are counted where the BRDF's sample meets
    // them, weighed against the emitters' sampling.
    if (depth == 0) sum += throughput * p.emissive;
    const glm::mat3 frame = tangentFrame(p.normal);
    const glm::mat3 toLocal = glm::transpose(frame);
    const glm::vec3 v = toLocal * view;
    // A probe capture leaves out the view-dependent specular of the surfaces the camera sees.
    const bool captured = depth == 0 && !o.cameraSeesSpecular;
    const ShadingTerms only = captured ? ShadingTerms::Diffuse : o.only;
    if (captured && o.captureMetalsAsDiffuse) p = metalAsDiffuse(p);
    const Brdf brdf = Brdf::of(p, v, only, o);
    const glm::vec3 origin = position + p.normal * 1e-4f * std::max(1.0f, glm::length(position));
    const auto unoccluded = [&](glm::vec3 w, float distance) {
      // Stop short of an area light's surface: the lights are not in the ray tracer.
      return !visibility ||
             !s.tracer.occluded(origin, w,
                                std::isfinite(distance) ? distance * (1.0f - 1e-4f) : INFINITY);
    };
    // Next-event estimation: one sample of each light (punctual lights exactly) and one of the
    // environment where no light hides it, each weighed against the BRDF's sampling.
    for (const Light& light : lights) {
      const LightSample ls = sampleLight(light, origin, sampler.uniform2());
      if (!(ls.delta || ls.pdf > 0.0f) || ls.radiance == glm::vec3(0.0f)) continue;
      const glm::vec3 l = toLocal * ls.direction;
      if (l.z <= 0.0f || !unoccluded(ls.direction, ls.distance)) continue;
      const float weight = ls.delta ? 1.0f : powerHeuristic(ls.pdf, brdf.pdf(v, l)) / ls.pdf;
      sum += throughput * brdf.evaluate(v, l, sampler) * ls.radiance * weight;
    }
    // One point on the emissive triangles (by power); without visibility the BRDF's samples are
    // not traced, so this sample takes all the weight. An analytic light in front hides it, as it
    // stops the BRDF's samples.
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
      if (es.pdf > 0.0f && es.radiance != glm::vec3(0.0f) && l.z > 0.0f &&
          unoccluded(es.direction, es.distance) && !lightInFront()) {
        const float weight =
            visibility ? powerHeuristic(es.pdf, brdf.pdf(v, l)) / es.pdf : 1.0f / es.pdf;
        sum += throughput * brdf.evaluate(v, l, sampler) * es.radiance * weight;
      }
    }
    if (o.environmentLight) {
      const glm::vec3 w = s.environment.sample(sampler.uniform2());
      const glm::vec3 l = toLocal * w;
      const float pe = s.environment.pdf(w);
      if (l.z > 0.0f && pe > 0.0f && nearestLight(lights, origin, w).index < 0 &&
          unoccluded(w, INFINITY))
        sum += throughput * brdf.evaluate(v, l, sampler) * s.environment.radiance(w) *
               (powerHeuristic(pe, brdf.pdf(v, l)) / pe);
    }
    // The BRDF's sample: it ends on a light or the environment (weighed against their
    // sampling), or goes on from the surface it meets.
    const Brdf::Sample bs = brdf.sample(v, sampler);
    const glm::vec3 l = bs.direction;
    const float pb = brdf.pdf(v, l);
    if (!(pb > 0.0f) || bs.weight == glm::vec3(0.0f)) break;
    const glm::vec3 w = frame * l;
    // f such that f / pb is the sample's weight: f cos / p of the sampled lobe (with the
    // microfacet walk an estimate of it, pb the MIS weights' approximate pdf; Brdf::sample).
    const glm::vec3 f = bs.weight * pb;
    const Ray ray{origin, w};
    const RayTracer::Hit hit = visibility ? s.tracer.intersect(ray) : RayTracer::Hit{};
    const NearestLight seen = nearestLight(lights, origin, w);
    if (seen.index >= 0 && (!hit.found || seen.hit.distance < hit.t)) {
      const Light& light = lights[static_cast<std::size_t>(seen.index)];
      const float pl = lightPdf(light, origin, w);
      sum += throughput * f * seen.hit.radiance * lightWindow(light, position) *
             (powerHeuristic(pb, pl) / pb);
      break;
    }
    if (!hit.found) {
      if (o.environmentLight)
        sum += throughput * f * s.environment.radiance(w) *
               (powerHeuristic(pb, s.environment.pdf(w)) / pb);
      break;
    }
    // An emissive surface met: its emission, weighed against the sampling of the emitters.
    const bool sphere = s.tracer.isSphere(hit.geometry);
    const Material& met = s.scene.materials[static_cast<std::size_t>(
        sphere ? s.scene.spheres[hit.primitive].material : s.scene.meshes[hit.geometry].material)];
    std::optional<SurfacePoint> next;
    if (met.emissive != glm::vec3(0.0f)) {
      next = surfaceAt(s.scene, s.tracer, hit, ray);
      const float pe = sphere ? 0.0f : s.emitters.pdf(w, hit.t, hit.geometry, hit.primitive);
      sum += throughput * f * next->emissive * (powerHeuristic(pb, pe) / pb);
    }
    if (depth >= o.bounces) break;
    throughput *= f / pb;
    // Russian roulette after two bounces: go on with the probability of the throughput.
    if (depth >= 1) {
      const float q = std::min(maxComponent(throughput), 0.95f);
      if (!(sampler.uniform() < q)) break;
      throughput /= q;
    }
    p = next ? *next : surfaceAt(s.scene, s.tracer, hit, ray);
    position = ray.origin + hit.t * ray.direction;
    view = -w;
  }
  return sum;
}

}  // namespace ibl
