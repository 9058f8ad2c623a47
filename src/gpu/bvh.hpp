#pragma once
// Internal to the device path tracer: the scene's triangles in a bounding volume hierarchy, built
// by Embree's generic builder (rtcBuildBVH) and flattened into the arrays the traversal of
// ibl/shared/bvh.h reads (on the device from storage buffers, on the host through view()).
#include <vector>

#include <glm/vec4.hpp>

#include "ibl/render/scene.hpp"
#include "ibl/shared/bvh.h"

namespace ibl::gpu {

struct Bvh {
  // Two vec4 per node, the root first: (boundsMin.xyz, a), (boundsMax.xyz, b) with a and b
  // uint bit patterns stored in the floats (std::bit_cast): an inner node has a = index of the
  // left child node, b = index of the right child node; a leaf has a = its first triangle,
  // b = 0x80000000u | triangle count.
  std::vector<glm::vec4> nodes;
  // Three vec4 per triangle, in leaf order: (v0.xyz, bits(mesh index)), (v1.xyz, bits(primitive
  // index within that mesh)), (v2.xyz, 0).
  std::vector<glm::vec4> triangles;

  // The arrays as bvhIntersect reads them on the host; `covers` may be null (every hit covers).
  shared::BvhView view(bool (*covers)(const void* user, int triangle, float u, float v,
                                      glm::vec3 origin, glm::vec3 dir) = nullptr,
                       const void* user = nullptr) const {
    return {nodes.data(), triangles.data(), covers, user};
  }
};

// The triangles of every mesh of `scene` (Scene::meshes, world space; spheres are not included,
// nor triangles with a non-finite vertex, which Embree ignores too) in a BVH built by Embree's
// rtcBuildBVH (binned SAH, RTC_BUILD_QUALITY_MEDIUM: no spatial splits, so each triangle is in
// one leaf; binary nodes; leaves of at most 4 triangles; depth at most 32), flattened depth
// first. An empty scene gives one empty leaf (inverted bounds). Throws Error("embree: ...").
Bvh buildBvh(const Scene& scene);

}  // namespace ibl::gpu
