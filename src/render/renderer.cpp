#include "ibl/render/renderer.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <numbers>

#include <embree3/rtcore.h>
#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "ibl/bake/dfg.hpp"
#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/math/brdf.hpp"
#include "ibl/math/color.hpp"
#include "ibl/math/sampling.hpp"
#include "ibl/render/light_sampling.hpp"
#include "ibl/render/ltc.hpp"
#include "ibl/shared/lights.h"
#include "ibl/shared/material.h"
#include "ibl/shared/split_sum.h"

namespace ibl {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kMinAlpha = 1e-3f;  // GGX of alpha 0 is a delta; 1e-3 is a mirror in practice

// PCG32 (O'Neill 2014): small, fast, and one stream per pixel makes renders reproducible.
class Random {
 public:
  Random(std::uint64_t seed, std::uint64_t stream) : inc_((stream << 1u) | 1u) {
    next();
    state_ += seed;
    next();
  }
  float uniform() { return static_cast<float>(next() >> 8) * (1.0f / 16777216.0f); }
  glm::vec2 uniform2() { return {uniform(), uniform()}; }

 private:
  std::uint32_t next() {
    const std::uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }
  std::uint64_t state_ = 0, inc_;
};

// The environment of the reference: a cube level taken as constant over each texel, sampled
// in proportion to luminance x solid angle (a texel, then a point uniform on its face-plane
// square), so that pdf(w) = p_texel / (A_texel rho(w)) with rho = (1 + sc^2 + tc^2)^(-3/2).
class EnvironmentSampler {
 public:
  explicit EnvironmentSampler(const std::array<Image, kFaceCount>& level)
      : level_(level), n_(level[0].width) {
    const std::size_t count = static_cast<std::size_t>(kFaceCount) * n_ * n_;
    cdf_.resize(count);
    double mean = 0.0;
    for (int f = 0; f < kFaceCount; ++f)
      for (const auto& p : level[f].pixels) mean += luminance(p);
    mean /= static_cast<double>(count);
    double total = 0.0;
    std::size_t i = 0;
    const std::vector<double> omega = faceTexelSolidAngles(n_);
    for (int f = 0; f < kFaceCount; ++f)
      for (int y = 0; y < n_; ++y)
        for (int x = 0; x < n_; ++x, ++i) {
          // A floor keeps every texel reachable, for MIS and for colors of low luminance.
          total += (luminance(level[f].at(x, y)) + 1e-3 * mean + 1e-12) *
                   omega[static_cast<std::size_t>(y) * n_ + x];
          cdf_[i] = total;
        }
    for (auto& c : cdf_) c /= total;
    texelArea_ = 4.0f / static_cast<float>(n_ * n_);
  }

  glm::vec3 radiance(glm::vec3 dir) const {
    const auto [face, x, y] = texelOf(dir);
    return level_[face].at(x, y);
  }

  float pdf(glm::vec3 dir) const {
    const auto [face, x, y] = texelOf(dir);
    const std::size_t i = (static_cast<std::size_t>(face) * n_ + y) * n_ + x;
    const double p = cdf_[i] - (i > 0 ? cdf_[i - 1] : 0.0);
    const FacePoint fp = directionToFace(dir);
    const float sc = 2.0f * fp.s - 1.0f, tc = 2.0f * fp.t - 1.0f;
    const float invRho = std::pow(1.0f + sc * sc + tc * tc, 1.5f);
    return static_cast<float>(p) * invRho / texelArea_;
  }

  glm::vec3 sample(glm::vec2 xi) const {
    const auto it = std::lower_bound(cdf_.begin(), cdf_.end(), static_cast<double>(xi.x));
    const auto i = static_cast<std::size_t>(
        std::min<std::ptrdiff_t>(it - cdf_.begin(), static_cast<std::ptrdiff_t>(cdf_.size()) - 1));
    const double lo = i > 0 ? cdf_[i - 1] : 0.0;
    // Reuse the position of xi.x within the texel's interval as the first coordinate.
    const float u =
        static_cast<float>(std::clamp((xi.x - lo) / std::max(cdf_[i] - lo, 1e-30), 0.0, 1.0));
    const int face = static_cast<int>(i / (static_cast<std::size_t>(n_) * n_));
    const int y = static_cast<int>(i / n_ % n_), x = static_cast<int>(i % n_);
    const float inv = 2.0f / static_cast<float>(n_);
    return glm::normalize(faceToDirection(face, (static_cast<float>(x) + u) * inv - 1.0f,
                                          (static_cast<float>(y) + xi.y) * inv - 1.0f));
  }

 private:
  struct TexelIndex {
    int face, x, y;
  };
  TexelIndex texelOf(glm::vec3 dir) const {
    const FacePoint p = directionToFace(dir);
    return {p.face, std::clamp(static_cast<int>(p.s * static_cast<float>(n_)), 0, n_ - 1),
            std::clamp(static_cast<int>(p.t * static_cast<float>(n_)), 0, n_ - 1)};
  }
  const std::array<Image, kFaceCount>& level_;
  int n_;
  std::vector<double> cdf_;
  float texelArea_;
};

// A ray from origin along dir, from distance 0 to infinity, seeing every geometry.
RTCRay embreeRay(glm::vec3 origin, glm::vec3 dir) {
  RTCRay ray{};
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.dir_x = dir.x;
  ray.dir_y = dir.y;
  ray.dir_z = dir.z;
  ray.tnear = 0.0f;
  ray.tfar = INFINITY;
  ray.mask = 0xffffffffu;
  return ray;
}

// What a mesh whose material is MASK or BLEND needs to decide whether a hit covers.
struct AlphaTest {
  const Mesh* mesh;
  const Material* material;
  const Texture* texture;  // the base color texture, or null
};

// The material's alpha at a hit (barycentrics u, v of triangle `primitive`).
float alphaAt(const AlphaTest& a, unsigned primitive, float u, float v) {
  float alpha = a.material->baseColorAlpha;
  const std::vector<glm::vec2>& uvs =
      a.material->baseColorTexture.texCoord == 1 ? a.mesh->uvs1 : a.mesh->uvs;
  if (a.texture && !uvs.empty()) {
    const std::uint32_t* i = &a.mesh->indices[3 * static_cast<std::size_t>(primitive)];
    const glm::vec2 uv = uvs[i[0]] * (1.0f - u - v) + uvs[i[1]] * u + uvs[i[2]] * v;
    alpha *= a.texture->sample(uv, false).w;
  }
  return alpha;
}

// A uniform number in [0, 1) from a ray and a triangle: the threshold of stochastic
// transparency (each sample's ray differs, so BLEND averages to alpha over samples).
float blendThreshold(const float (&ray)[6], unsigned primitive) {
  std::uint32_t h = primitive * 0x9e3779b9u;
  for (float f : ray) {
    h ^= std::bit_cast<std::uint32_t>(f) + 0x7f4a7c15u + (h << 6) + (h >> 2);
    h *= 0x85ebca6bu;
    h ^= h >> 13;
  }
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return static_cast<float>(h >> 8) * 0x1p-24f;
}

// Embree's filter for MASK and BLEND meshes, of intersections and of occlusion alike: a hit the
// alpha does not cover is ignored, and the ray goes on.
void alphaFilter(const RTCFilterFunctionNArguments* args) {
  const auto* a = static_cast<const AlphaTest*>(args->geometryUserPtr);
  for (unsigned k = 0; k < args->N; ++k) {
    if (args->valid[k] != -1) continue;
    const unsigned primitive = RTCHitN_primID(args->hit, args->N, k);
    const float alpha =
        alphaAt(*a, primitive, RTCHitN_u(args->hit, args->N, k), RTCHitN_v(args->hit, args->N, k));
    const float ray[6] = {
        RTCRayN_org_x(args->ray, args->N, k), RTCRayN_org_y(args->ray, args->N, k),
        RTCRayN_org_z(args->ray, args->N, k), RTCRayN_dir_x(args->ray, args->N, k),
        RTCRayN_dir_y(args->ray, args->N, k), RTCRayN_dir_z(args->ray, args->N, k)};
    if (!shared::alphaCovers(static_cast<int>(a->material->alphaMode), alpha,
                             a->material->alphaCutoff, blendThreshold(ray, primitive)))
      args->valid[k] = 0;
  }
}

// Embree scene of the meshes (one geometry each) and the spheres (one geometry).
class RayTracer {
 public:
  explicit RayTracer(const Scene& scene) : scene_(scene) {
    device_ = rtcNewDevice(nullptr);
    if (!device_) fail("embree", "cannot create a device");
    handle_ = rtcNewScene(device_);
    rtcSetSceneFlags(handle_, RTC_SCENE_FLAG_COMPACT);
    alphaTests_.reserve(scene.meshes.size());  // stable addresses: Embree keeps pointers
    for (const Mesh& m : scene.meshes) {
      RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.positions.size()));
      for (std::size_t i = 0; i < m.positions.size(); ++i)
        for (int c = 0; c < 3; ++c) v[3 * i + c] = m.positions[i][c];
      // The scene outlives the tracer: Embree reads the mesh's triangles where they are.
      rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0,
                                 3 * sizeof(std::uint32_t), m.indices.size() / 3);
      const Material& mat = scene.materials[m.material];
      if (mat.alphaMode != AlphaMode::Opaque) {
        const int t = mat.baseColorTexture.index;
        alphaTests_.push_back({&m, &mat, t >= 0 ? &scene.textures[t] : nullptr});
        rtcSetGeometryUserData(g, &alphaTests_.back());
        rtcSetGeometryIntersectFilterFunction(g, alphaFilter);
        rtcSetGeometryOccludedFilterFunction(g, alphaFilter);
      }
      rtcCommitGeometry(g);
      rtcAttachGeometry(handle_, g);
      rtcReleaseGeometry(g);
    }
    if (!scene.spheres.empty()) {
      RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                            RTC_FORMAT_FLOAT4, 4 * sizeof(float),
                                                            scene.spheres.size()));
      for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
        for (int c = 0; c < 3; ++c) v[4 * i + c] = scene.spheres[i].center[c];
        v[4 * i + 3] = scene.spheres[i].radius;
      }
      rtcCommitGeometry(g);
      sphereGeometry_ = rtcAttachGeometry(handle_, g);
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(handle_);
  }
  ~RayTracer() {
    rtcReleaseScene(handle_);
    rtcReleaseDevice(device_);
  }
  RayTracer(const RayTracer&) = delete;
  RayTracer& operator=(const RayTracer&) = delete;

  struct Hit {
    bool found = false;
    float t = 0.0f;
    unsigned geometry = 0, primitive = 0;
    float u = 0.0f, v = 0.0f;
    glm::vec3 ng{0.0f};
  };

  Hit intersect(const Ray& r) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray = embreeRay(r.origin, r.direction);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(handle_, &context, &rh);
    Hit h;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    h.found = true;
    h.t = rh.ray.tfar;
    h.geometry = rh.hit.geomID;
    h.primitive = rh.hit.primID;
    h.u = rh.hit.u;
    h.v = rh.hit.v;
    h.ng = glm::normalize(glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    return h;
  }

  // Is anything between origin and origin + maxDistance dir?
  bool occluded(glm::vec3 origin, glm::vec3 dir, float maxDistance = INFINITY) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = embreeRay(origin, dir);
    ray.tfar = maxDistance;
    rtcOccluded1(handle_, &context, &ray);
    return ray.tfar < 0.0f;
  }

  bool isSphere(unsigned geometry) const {
    return !scene_.spheres.empty() && geometry == sphereGeometry_;
  }

 private:
  const Scene& scene_;
  std::vector<AlphaTest> alphaTests_;
  RTCDevice device_ = nullptr;
  RTCScene handle_ = nullptr;
  unsigned sphereGeometry_ = RTC_INVALID_GEOMETRY_ID;
};

// The shading point of a hit: interpolated attributes, material textures, normal mapping.
SurfacePoint surfaceAt(const Scene& scene, const RayTracer& tracer, const RayTracer::Hit& hit,
                       const Ray& ray) {
  SurfacePoint p{};
  const Material* mat;
  glm::vec3 n;
  if (tracer.isSphere(hit.geometry)) {
    const Sphere& s = scene.spheres[hit.primitive];
    n = glm::normalize(ray.origin + hit.t * ray.direction - s.center);
    mat = &scene.materials[s.material];
    p.baseColor = mat->baseColor;
    p.metallic = mat->metallic;
    p.roughness = mat->roughness;
    p.emissive = mat->emissive;
  } else {
    const Mesh& m = scene.meshes[hit.geometry];
    mat = &scene.materials[m.material];
    const std::uint32_t i0 = m.indices[3 * hit.primitive], i1 = m.indices[3 * hit.primitive + 1],
                        i2 = m.indices[3 * hit.primitive + 2];
    const float w0 = 1.0f - hit.u - hit.v, w1 = hit.u, w2 = hit.v;
    n = glm::normalize(m.normals[i0] * w0 + m.normals[i1] * w1 + m.normals[i2] * w2);
    glm::vec3 base = mat->baseColor;
    float metallic = mat->metallic, roughness = mat->roughness;
    glm::vec3 emissive = mat->emissive;
    // Each slot reads its own UV set (glTF texCoord); a slot whose set the mesh lacks is off.
    const auto lookup = [&](const TextureRef& ref, bool srgb, glm::vec4& texel) {
      const std::vector<glm::vec2>& uvs = ref.texCoord == 1 ? m.uvs1 : m.uvs;
      if (ref.index < 0 || uvs.empty()) return false;
      const glm::vec2 uv = uvs[i0] * w0 + uvs[i1] * w1 + uvs[i2] * w2;
      texel = scene.textures[ref.index].sample(uv, srgb);
      return true;
    };
    glm::vec4 t;
    if (lookup(mat->baseColorTexture, true, t)) base *= glm::vec3(t);
    if (lookup(mat->metallicRoughnessTexture, false, t)) {
      const glm::vec2 mr = shared::applyMetallicRoughnessTexel(metallic, roughness, t);
      metallic = mr.x;
      roughness = mr.y;
    }
    if (lookup(mat->occlusionTexture, false, t))
      p.occlusion = shared::occlusionFromTexel(mat->occlusionStrength, t);
    if (lookup(mat->emissiveTexture, true, t)) emissive *= glm::vec3(t);
    if (!m.tangents.empty() && lookup(mat->normalTexture, false, t)) {
      const glm::vec4 t4 = m.tangents[i0] * w0 + m.tangents[i1] * w1 + m.tangents[i2] * w2;
      n = shared::applyNormalMap(n, t4, t, mat->normalScale);
    }
    p.baseColor = base;
    p.metallic = std::clamp(metallic, 0.0f, 1.0f);
    p.roughness = std::clamp(roughness, 0.0f, 1.0f);
    p.emissive = emissive;
  }
  // Shade the side the ray sees.
  if (glm::dot(n, ray.direction) > 0.0f) n = -n;
  p.normal = n;
  return p;
}

// The material's BRDF pieces at one point.
struct Brdf {
  glm::vec3 diffuseColor, f0;
  float alpha, roughness;
  DiffuseModel diffuseModel;
  ShadingTerms only;

  static Brdf of(const SurfacePoint& p, const RenderOptions& o) {
    return {p.baseColor * (1.0f - p.metallic),
            glm::mix(glm::vec3(0.04f), p.baseColor, p.metallic),
            std::max(alphaFromRoughness(p.roughness), kMinAlpha),
            p.roughness,
            o.diffuse,
            o.only};
  }

  // f(v, l) (n.l), with n = +Z of the local frame.
  glm::vec3 evaluate(glm::vec3 v, glm::vec3 l) const {
    const float NoV = std::max(v.z, 1e-4f), NoL = l.z;
    if (NoL <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 h = glm::normalize(v + l);
    glm::vec3 result(0.0f);
    if (only != ShadingTerms::Diffuse) {
      const float VoH = std::max(glm::dot(v, h), 0.0f);
      result += ggxDistribution(h.z, alpha) * smithGgxCorrelatedVisibility(NoV, NoL, alpha) *
                fresnelSchlick(f0, 1.0f, VoH);
    }
    if (only != ShadingTerms::Specular) {
      const float fd = diffuseModel == DiffuseModel::Disney
                           ? disneyDiffuseRenormalized(NoV, NoL, glm::dot(l, h), roughness)
                           : 1.0f;
      result += diffuseColor * (fd / kPi);
    }
    return result * NoL;
  }

  // Probability of picking the specular lobe when sampling.
  float specularProbability() const {
    if (only == ShadingTerms::Diffuse) return 0.0f;
    if (only == ShadingTerms::Specular) return 1.0f;
    const float s = luminance(f0) + 0.04f, d = luminance(diffuseColor);
    if (d <= 0.0f) return 1.0f;  // a metal: no diffuse lobe to sample
    return std::clamp(s / (s + d), 0.1f, 0.9f);
  }

  float pdf(glm::vec3 v, glm::vec3 l) const {
    if (l.z <= 0.0f) return 0.0f;
    const float ps = specularProbability();
    float p = (1.0f - ps) * l.z / kPi;
    if (ps > 0.0f) {
      const glm::vec3 h = glm::normalize(v + l);
      const float NoV = std::max(v.z, 1e-4f);
      // Visible normals, reflected: pdf(l) = G1(v) D(h) / (4 n.v).
      p += ps * smithGgxMasking(NoV, alpha) * ggxDistribution(h.z, alpha) / (4.0f * NoV);
    }
    return p;
  }

  glm::vec3 sample(glm::vec3 v, glm::vec2 xi, float choose) const {
    if (choose < specularProbability()) {
      const glm::vec3 h = sampleGgxVisibleNormal(v, xi, alpha);
      return 2.0f * glm::dot(v, h) * h - v;
    }
    return sampleCosineHemisphere(xi);
  }
};

float powerHeuristic(float a, float b) {
  return a * a / (a * a + b * b);
}

// The nearest light the ray from p along w meets (lights do not hide one another beyond that):
// its index, or -1.
struct NearestLight {
  int index = -1;
  LightHit hit;
};
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

// One Monte Carlo estimate of the reflected radiance: per light, one light sample (punctual
// lights exactly); one BRDF sample, which sees the nearest light or else the environment; one
// environment sample. The sampled strategies are combined by multiple importance sampling
// with the power heuristic (Veach 1997, section 9.2).
glm::vec3 estimateReference(const SurfacePoint& p, glm::vec3 position, glm::vec3 view,
                            const EnvironmentSampler& env, const std::vector<Light>& lights,
                            const RayTracer& tracer, const RenderOptions& o, Random& rng) {
  const glm::mat3 frame = tangentFrame(p.normal);
  const glm::mat3 toLocal = glm::transpose(frame);
  const glm::vec3 v = toLocal * view;
  const Brdf brdf = Brdf::of(p, o);
  const glm::vec3 offset = p.normal * 1e-4f * std::max(1.0f, glm::length(position));
  const auto visible = [&](glm::vec3 worldDir, float distance) {
    // Stop short of an area light's surface: the light itself is not in the ray tracer.
    return !o.shadows ||
           !tracer.occluded(position + offset, worldDir,
                            std::isfinite(distance) ? distance * (1.0f - 1e-4f) : INFINITY);
  };
  glm::vec3 sum(0.0f);
  for (const Light& light : lights) {  // light samples
    const LightSample ls = sampleLight(light, position + offset, rng.uniform2());
    if (!(ls.delta || ls.pdf > 0.0f) || ls.radiance == glm::vec3(0.0f)) continue;
    const glm::vec3 l = toLocal * ls.direction;
    if (l.z <= 0.0f || !visible(ls.direction, ls.distance)) continue;
    if (ls.delta) {
      sum += brdf.evaluate(v, l) * ls.radiance;
    } else {
      sum += brdf.evaluate(v, l) * ls.radiance * (powerHeuristic(ls.pdf, brdf.pdf(v, l)) / ls.pdf);
    }
  }
  {  // BRDF sample
    const glm::vec3 l = brdf.sample(v, rng.uniform2(), rng.uniform());
    const float pb = brdf.pdf(v, l);
    if (pb > 0.0f) {
      const glm::vec3 w = frame * l;
      const NearestLight hit = nearestLight(lights, position + offset, w);
      if (hit.index >= 0) {
        const Light& light = lights[static_cast<std::size_t>(hit.index)];
        const float pl = lightPdf(light, position + offset, w);
        if (hit.hit.radiance != glm::vec3(0.0f) && visible(w, hit.hit.distance))
          sum += brdf.evaluate(v, l) * hit.hit.radiance * lightWindow(light, position) *
                 (powerHeuristic(pb, pl) / pb);
      } else if (o.environmentLight && visible(w, INFINITY)) {
        sum += brdf.evaluate(v, l) * env.radiance(w) * (powerHeuristic(pb, env.pdf(w)) / pb);
      }
    }
  }
  if (o.environmentLight) {  // environment sample (where no light hides the environment)
    const glm::vec3 w = env.sample(rng.uniform2());
    const glm::vec3 l = toLocal * w;
    const float pe = env.pdf(w);
    if (l.z > 0.0f && pe > 0.0f && nearestLight(lights, position + offset, w).index < 0 &&
        visible(w, INFINITY))
      sum += brdf.evaluate(v, l) * env.radiance(w) * (powerHeuristic(pe, brdf.pdf(v, l)) / pe);
  }
  return sum + p.emissive;
}

}  // namespace

shared::SplitSumSwitches splitSumSwitches(const RenderOptions& o) {
  shared::SplitSumSwitches s;
  s.terms = o.only == ShadingTerms::Diffuse ? 1 : (o.only == ShadingTerms::Specular ? 2 : 0);
  s.multipleScattering = o.multipleScattering;
  s.dominantDirections = o.dominantDirections;
  s.specularOcclusion = o.specularOcclusion;
  s.disneyDiffuse = o.diffuse == DiffuseModel::Disney;
  s.ltcAreaLights = o.areaLights == AreaLightModel::Ltc;
  return s;
}

glm::vec3 shadeSplitSum(const SurfacePoint& p, glm::vec3 view, const BakeResult& bake,
                        const BakeOptions& bakeOptions, const RenderOptions& o) {
  // The formulas are ibl/shared/split_sum.h (the viewer's shader calls the same); only the
  // three lookups are the CPU's own: seam-aware trilinear and bilinear, the DFG table.
  const shared::SplitSumSwitches s = splitSumSwitches(o);
  const shared::SplitSumLookup look = shared::splitSumLookup(p.normal, view, p.roughness, s);
  const glm::vec3 dfg = sampleDfgLut(bake.dfg, look.NoV, p.roughness);
  glm::vec3 prefiltered(0.0f), irradiance(0.0f);
  if (o.environmentLight && o.only != ShadingTerms::Diffuse) {
    const float lod = specularLodForRoughness(p.roughness, bake.specular.levelCount(),
                                              bakeOptions.specular.mapping);
    prefiltered = sampleTrilinear(bake.specular, lod, look.specularDirection);
  }
  if (o.environmentLight && o.only != ShadingTerms::Specular)
    irradiance = o.irradiance == IrradianceSource::Cube
                     ? sampleBilinear(bake.irradiance, 0, look.diffuseDirection)
                     : irradianceSh9(bake.sh, look.diffuseDirection) / kPi;
  shared::SplitSumMaterial m;
  m.baseColor = p.baseColor;
  m.metallic = p.metallic;
  m.roughness = p.roughness;
  m.occlusion = p.occlusion;
  m.emissive = p.emissive;
  return shared::splitSumRadiance(m, look.NoV, dfg, prefiltered, irradiance, s);
}

glm::vec3 shadeLightsRealTime(const SurfacePoint& p, glm::vec3 position, glm::vec3 view,
                              const std::vector<Light>& lights, glm::vec2 dfg,
                              const RenderOptions& o) {
  const shared::SplitSumSwitches s = splitSumSwitches(o);
  shared::SplitSumMaterial m;
  m.baseColor = p.baseColor;
  m.metallic = p.metallic;
  m.roughness = p.roughness;
  m.occlusion = 1.0f;  // ambient occlusion darkens indirect light only
  m.emissive = glm::vec3(0.0f);
  const glm::vec4 ltc = s.ltcAreaLights
                            ? ltcTableLookup(p.roughness, std::max(glm::dot(p.normal, view), 1e-4f))
                            : glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  glm::vec3 sum(0.0f);
  for (const Light& light : lights) {
    const shared::ShadingLight sl = shadingLightOf(light);
    const shared::LightIncidence inc =
        shared::lightIncidence(sl, position, p.normal, view, p.roughness, s, ltc);
    const float profile =
        light.ies ? light.intensityToward(glm::normalize(position - light.position)) : 1.0f;
    sum += sl.color * profile * shared::lightRadiance(m, p.normal, view, inc, dfg, s);
  }
  return sum;
}

RenderResult renderScene(const Scene& scene, const Camera& camera, const BakeResult& bake,
                         const BakeOptions& bakeOptions, const RenderOptions& o,
                         const std::function<void(float)>& progress) {
  checkCamera(camera);
  const auto start = std::chrono::steady_clock::now();
  const RayTracer tracer(scene);
  const EnvironmentSampler env(bake.source.levels[0]);
  RenderResult result;
  result.color = Image(camera.width, camera.height);
  result.alpha.assign(static_cast<std::size_t>(camera.width) * camera.height, 0.0f);
  std::atomic<int> rowsDone{0};
  std::atomic<std::uint64_t> samples{0};
  const int spp = std::max(1, o.spp);
  parallelFor(0, camera.height, [&](int y) {
    std::uint64_t rowSamples = 0;
    for (int x = 0; x < camera.width; ++x) {
      Random rng(o.seed, static_cast<std::uint64_t>(y) * camera.width + x);
      glm::dvec3 sum(0.0);
      double lumSum = 0.0, lumSq = 0.0;
      int covered = 0, taken = 0;
      for (int s = 0; s < spp; ++s) {
        // Positions in the pixel from a scrambled Sobol sequence, decorrelated per pixel: any
        // prefix is spread over the whole pixel (for early stops and any spp); one sample is
        // the pixel center.
        const std::uint32_t pixel = static_cast<std::uint32_t>(y * camera.width + x);
        const glm::vec2 j =
            spp == 1 ? glm::vec2(0.5f)
                     : sobolOwen2D(static_cast<std::uint32_t>(s),
                                   pixel ^ static_cast<std::uint32_t>(o.seed * 0x9e3779b9u));
        const float jx = j.x, jy = j.y;
        const Ray ray = camera.generateRay(static_cast<float>(x) + jx, static_cast<float>(y) + jy);
        const RayTracer::Hit hit = tracer.intersect(ray);
        const NearestLight seen = nearestLight(scene.lights, ray.origin, ray.direction);
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
          const SurfacePoint p = surfaceAt(scene, tracer, hit, ray);
          const glm::vec3 position = ray.origin + hit.t * ray.direction;
          if (o.mode == RenderMode::SplitSum) {
            c = shadeSplitSum(p, -ray.direction, bake, bakeOptions, o);
            if (!scene.lights.empty()) {
              const float NoV = std::max(glm::dot(p.normal, -ray.direction), 1e-4f);
              const glm::vec3 dfg = sampleDfgLut(bake.dfg, NoV, p.roughness);
              c +=
                  shadeLightsRealTime(p, position, -ray.direction, scene.lights, glm::vec2(dfg), o);
            }
          } else {
            c = estimateReference(p, position, -ray.direction, env, scene.lights, tracer, o, rng);
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
      result.alpha[static_cast<std::size_t>(y) * camera.width + x] =
          static_cast<float>(covered) / static_cast<float>(taken);
      rowSamples += static_cast<std::uint64_t>(taken);
    }
    samples += rowSamples;
    const int done = ++rowsDone;
    if (progress && done % 16 == 0)
      progress(static_cast<float>(done) / static_cast<float>(camera.height));
  });
  result.samples = static_cast<double>(samples.load());
  result.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace ibl
