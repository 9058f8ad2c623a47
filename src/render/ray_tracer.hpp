#pragma once
// Internal to the renderer: the scene in Embree (triangle meshes, with MASK and BLEND alpha
// decided in Embree's filters, and the analytic spheres) and the shading point of a hit. The
// reference path tracer, the probe capture and the ambient-occlusion rays all trace through it.
#include <algorithm>
#include <cmath>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "ibl/render/camera.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/render/scene.hpp"

namespace ibl {

// What a mesh whose material is MASK or BLEND needs to decide whether a hit covers.
struct AlphaTest {
  const Mesh* mesh;
  const Material* material;
  const Texture* texture;  // the base color texture, or null
};

// A ray from origin along dir, from distance 0 to infinity, seeing every geometry.
RTCRay embreeRay(glm::vec3 origin, glm::vec3 dir);

// Embree scene of the meshes (one geometry each) and the spheres (one geometry); `scene` must
// outlive it.
class RayTracer {
 public:
  explicit RayTracer(const Scene& scene);
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

  // Which surfaces a ray sees (Embree's ray mask): those whose material transmits nothing, those
  // that transmit (KHR_materials_transmission), or all.
  static constexpr unsigned kOpaque = 1u, kTransmissive = 2u, kAll = 3u;
  static unsigned maskOf(const Material& material);

  // The first surface along r that `mask` sees. A sphere's hit has its index in the scene's
  // spheres as its primitive.
  Hit intersect(const Ray& r, unsigned mask = kAll) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray = embreeRay(r.origin, r.direction);
    rh.ray.mask = mask;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(handle_, &context, &rh);
    Hit h;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    h.found = true;
    h.t = rh.ray.tfar;
    h.geometry = rh.hit.geomID;
    h.primitive = rh.hit.primID;
    for (int k = 0; k < 2; ++k)
      if (h.geometry == sphereGeometries_[k]) h.primitive = sphereIndices_[k][h.primitive];
    h.u = rh.hit.u;
    h.v = rh.hit.v;
    h.ng = glm::normalize(glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    return h;
  }

  // Is anything that `mask` sees between origin and origin + maxDistance dir?
  bool occluded(glm::vec3 origin, glm::vec3 dir, float maxDistance = INFINITY,
                unsigned mask = kAll) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = embreeRay(origin, dir);
    ray.tfar = maxDistance;
    ray.mask = mask;
    rtcOccluded1(handle_, &context, &ray);
    return ray.tfar < 0.0f;
  }

  // Whether any material transmits (hasTransmission): where none does, kOpaque sees everything.
  bool transmits() const { return transmits_; }

  bool isSphere(unsigned geometry) const {
    return geometry != RTC_INVALID_GEOMETRY_ID &&
           (geometry == sphereGeometries_[0] || geometry == sphereGeometries_[1]);
  }

 private:
  const Scene& scene_;
  std::vector<AlphaTest> alphaTests_;
  RTCDevice device_ = nullptr;
  RTCScene handle_ = nullptr;
  // The spheres' geometries (those that transmit nothing, those that transmit; invalid when
  // there are none) and the scene's sphere of each of their primitives.
  unsigned sphereGeometries_[2] = {RTC_INVALID_GEOMETRY_ID, RTC_INVALID_GEOMETRY_ID};
  std::vector<std::uint32_t> sphereIndices_[2];
  bool transmits_ = false;
};

// The shading point of a hit: interpolated attributes, material textures, normal mapping; the
// normal faces the side the ray comes from.
SurfacePoint surfaceAt(const Scene& scene, const RayTracer& tracer, const RayTracer::Hit& hit,
                       const Ray& ray);

// Where `ray` meets the surface `hit` lies on, extended: the plane of its triangle (barycentrics
// outside [0, 1] extrapolate its attributes, as a fragment shader's helper invocations do), or
// its sphere (where the ray misses it, the point nearest the ray). For the differences of
// shading quantities between neighboring rays; t is not finite where the ray runs along the
// plane.
RayTracer::Hit hitOnSameSurface(const Scene& scene, const RayTracer& tracer,
                                const RayTracer::Hit& hit, const Ray& ray);

// The material of the surface a hit met.
const Material& hitMaterial(const Scene& scene, const RayTracer& tracer, const RayTracer::Hit& hit);

// The first surface along `ray` whose material transmits nothing (KHR_materials_transmission).
inline RayTracer::Hit firstOpaqueHit(const RayTracer& tracer, const Ray& ray) {
  return tracer.intersect(ray, RayTracer::kOpaque);
}

// Where crossTransmissive stops: 1e-5 past `end` (at least 1e-5 scene units: a glass resting on
// a table is in front of it), or at `end` exactly (a light's own point).
enum class CrossingEnd { Past, Exact };

// Hands each surface that transmits along `ray` up to distance `end` (CrossingEnd: included, and
// 1e-5 past it by default) to crossed(hit, segment, distance), in order, up to 256 of them:
// the hit along `segment`, the part of `ray` that starts just past the previous one (the same
// direction), and its distance along `ray`.
template <class Crossed>
void crossTransmissive(const RayTracer& tracer, const Ray& ray, float end, Crossed&& crossed,
                       CrossingEnd stop = CrossingEnd::Past) {
  const float last = stop == CrossingEnd::Exact ? end : end + 1e-5f * std::max(1.0f, end);
  float travelled = 0.0f;
  Ray rest = ray;
  for (int surfaces = 0; surfaces < 256; ++surfaces) {
    const RayTracer::Hit hit = tracer.intersect(rest, RayTracer::kTransmissive);
    if (!hit.found || travelled + hit.t > last) return;
    crossed(hit, rest, travelled + hit.t);
    const glm::vec3 at = rest.origin + hit.t * rest.direction;
    const float step = hit.t + 1e-4f * std::max(1.0f, glm::length(at));
    rest.origin += step * rest.direction;
    travelled += step;
  }
}

}  // namespace ibl
