#pragma once
// Internal to the renderer: the scene in Embree (triangle meshes, with MASK and BLEND alpha
// decided in Embree's filters, and the analytic spheres) and the shading point of a hit. The
// reference path tracer, the probe capture and the ambient-occlusion rays all trace through it.
#include <cmath>
#include <vector>

#include <embree3/rtcore.h>
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

// The shading point of a hit: interpolated attributes, material textures, normal mapping; the
// normal faces the side the ray comes from.
SurfacePoint surfaceAt(const Scene& scene, const RayTracer& tracer, const RayTracer::Hit& hit,
                       const Ray& ray);

}  // namespace ibl
