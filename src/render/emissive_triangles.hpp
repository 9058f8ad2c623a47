#pragma once
// Internal to the renderer: the scene's emissive triangles as lights of the reference. The path
// tracer samples them in next-event estimation, a triangle in proportion to its power (emitted
// luminance x area, both faces), then a point uniform over its area, and weighs the sample
// against the BRDF's by multiple importance sampling (Veach 1997, section 9.2; pbrt-v4 12.3 and
// 13.4). A BRDF sample that meets an emissive triangle is weighed with the density here.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibl/render/scene.hpp"

namespace ibl {

class RayTracer;

struct EmitterSample {
  glm::vec3 direction{0.0f};  // unit, from the shaded point toward the sampled point
  float distance = 0.0f;
  glm::vec3 radiance{0.0f};  // the emission seen along -direction (the texture applied)
  float pdf = 0.0f;          // per solid angle at the shaded point; 0: nothing to add
};

class EmissiveTriangles {
 public:
  // Every triangle of the scene's meshes whose material emits (its emissive factor, times the
  // mean of its emissive texture, above 0). Spheres are not sampled: the built-in scenes do not
  // emit.
  EmissiveTriangles(const Scene& scene, const RayTracer& tracer);

  bool empty() const { return triangles_.empty(); }
  std::size_t size() const { return triangles_.size(); }

  // A point on an emissive triangle seen from p, with xi uniform in [0, 1)^3 (x picks the
  // triangle, y and z the point).
  EmitterSample sample(glm::vec3 p, glm::vec3 xi) const;

  // The density per solid angle with which sample(p, .) picks the point at distance t from p
  // along unit w on triangle `primitive` of mesh `mesh` (0 when that triangle is not sampled).
  float pdf(glm::vec3 w, float t, unsigned mesh, unsigned primitive) const;

  // What is sampled, for the GPU reference's copy: each triangle, its area and the cumulative
  // probability up to and including it (the last 1), and per mesh and primitive the triangle's
  // entry (-1: not sampled; a mesh without emitters has no entries).
  struct Triangle {
    unsigned mesh, primitive;
    float area;
  };
  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<double>& cumulative() const { return cdf_; }
  const std::vector<std::vector<std::int32_t>>& entryOf() const { return indexOf_; }

 private:
  const Scene& scene_;
  const RayTracer& tracer_;
  std::vector<Triangle> triangles_;
  std::vector<double> cdf_;  // of the triangles' power, normalized
  // Per mesh, the first entry of its triangles in triangles_ and the index of each primitive
  // there (-1: it does not emit), for pdf().
  std::vector<std::vector<std::int32_t>> indexOf_;
};

}  // namespace ibl
