// API: internal (may change without notice; math shared with the shaders)
// Rays against the scene's triangles in a binary BVH (built on the host by Embree's generic
// builder, src/gpu/bvh.hpp, whose comments give the layout), traversed alike by the CPU and the
// GPU path tracer. C++ and GLSL (see lang.h). The hierarchy is read through accessors each
// language defines: bvhNodeAt(i), bvhTriangleAt(i) (vec4 i of either array) and bvhCovers
// (alpha masking: a rejected hit does not shorten the ray); in C++ they take a BvhView first
// (IBL_BVH / IBL_BVH_ARG below), in GLSL the shader defines them over its storage buffers.
//
// Boxes: slabs with a precomputed inverse direction (Williams et al. 2005, "An Efficient and
// Robust Ray-Box Intersection Algorithm"), the exit widened by 2 gamma(3) so that rounding
// cannot miss a box the ray crosses (Ize 2013, "Robust BVH Ray Traversal"), nearer child first.
// Triangles: Möller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection",
// two-sided. The stack holds 64 nodes; the builder limits the depth to 32.
#ifndef IBL_SHARED_BVH_H
#define IBL_SHARED_BVH_H
#include "ibl/shared/lang.h"

#ifdef __cplusplus
#include <bit>
#endif

IBL_BEGIN

// What a ray hits: the triangle (index into the triangles, in leaf order), its distance and the
// barycentric weights of its vertices 1 and 2 (the point is (1 - u - v) v0 + u v1 + v v2).
struct BvhHit {
  bool found;
  float t;
  int triangle;
  float u;
  float v;
};

#ifdef __cplusplus
// The hierarchy as the CPU holds it (gpu::Bvh owns it); covers null: every hit covers.
struct BvhView {
  const vec4* nodes;
  const vec4* triangles;
  bool (*covers)(const void* user, int triangle, float u, float v, vec3 origin, vec3 dir);
  const void* user;
};
inline vec4 bvhNodeAt(const BvhView& bvh, int i) {
  return bvh.nodes[i];
}
inline vec4 bvhTriangleAt(const BvhView& bvh, int i) {
  return bvh.triangles[i];
}
inline bool bvhCovers(const BvhView& bvh, int triangle, float u, float v, vec3 origin, vec3 dir) {
  return bvh.covers == nullptr || bvh.covers(bvh.user, triangle, u, v, origin, dir);
}
inline uint bvhFloatBits(float f) {
  return std::bit_cast<uint>(f);
}
#define IBL_BVH const BvhView &bvh,
#define IBL_BVH_ARG bvh,
#else
#define IBL_BVH
#define IBL_BVH_ARG
// Defined by the shader over its buffers.
vec4 bvhNodeAt(int i);
vec4 bvhTriangleAt(int i);
bool bvhCovers(int triangle, float u, float v, vec3 origin, vec3 dir);
uint bvhFloatBits(float f) {
  return floatBitsToUint(f);
}
#endif

// 1 / d, finite: a zero component gives a huge slope of its sign (no 0 * infinity in the slabs).
IBL_FN float bvhInverse(float d) {
  return abs(d) > 1e-30f ? 1.0f / d : (d >= 0.0f ? 1e30f : -1e30f);
}

// Where the ray enters node i's box (0 if it starts inside), or -1 if it misses the box or
// enters it beyond tMax.
IBL_FN float bvhBoxEntry(IBL_BVH int i, vec3 origin, vec3 invDir, float tMax) {
  vec3 t0 = (vec3(bvhNodeAt(IBL_BVH_ARG 2 * i)) - origin) * invDir;
  vec3 t1 = (vec3(bvhNodeAt(IBL_BVH_ARG 2 * i + 1)) - origin) * invDir;
  vec3 lo = min(t0, t1);
  vec3 hi = max(t0, t1);
  float enter = max(max(lo.x, lo.y), max(lo.z, 0.0f));
  float exit = min(min(hi.x, hi.y), hi.z) * 1.00000024f;
  return enter <= exit && enter <= tMax ? enter : -1.0f;
}

// (t, u, v) of the ray's hit on triangle (v0, v1, v2) from either side; t = -1 when it misses
// (or runs parallel to it).
IBL_FN vec3 bvhTriangleHit(vec3 origin, vec3 dir, vec3 v0, vec3 v1, vec3 v2) {
  vec3 e1 = v1 - v0;
  vec3 e2 = v2 - v0;
  vec3 p = cross(dir, e2);
  float det = dot(e1, p);
  if (det == 0.0f) return vec3(-1.0f);
  float inv = 1.0f / det;
  vec3 s = origin - v0;
  float u = dot(s, p) * inv;
  vec3 q = cross(s, e1);
  float v = dot(dir, q) * inv;
  if (!(u >= 0.0f && v >= 0.0f && u + v <= 1.0f)) return vec3(-1.0f);
  return vec3(dot(e2, q) * inv, u, v);
}

// The nearest covered hit with t in (0, tMax), or with anyHit the first one found.
IBL_FN BvhHit bvhIntersect(IBL_BVH vec3 origin, vec3 dir, float tMax, bool anyHit) {
  BvhHit hit;
  hit.found = false;
  hit.t = tMax;
  hit.triangle = -1;
  hit.u = 0.0f;
  hit.v = 0.0f;
  vec3 invDir = vec3(bvhInverse(dir.x), bvhInverse(dir.y), bvhInverse(dir.z));
  int stack[64];
  int top = 0;
  int node = bvhBoxEntry(IBL_BVH_ARG 0, origin, invDir, tMax) >= 0.0f ? 0 : -1;
  while (node >= 0) {
    uint a = bvhFloatBits(bvhNodeAt(IBL_BVH_ARG 2 * node).w);
    uint b = bvhFloatBits(bvhNodeAt(IBL_BVH_ARG 2 * node + 1).w);
    int next = -1;
    if ((b & 0x80000000u) != 0u) {
      int last = int(a) + int(b & 0x7fffffffu);
      for (int k = int(a); k < last; ++k) {
        vec3 r = bvhTriangleHit(origin, dir, vec3(bvhTriangleAt(IBL_BVH_ARG 3 * k)),
                                vec3(bvhTriangleAt(IBL_BVH_ARG 3 * k + 1)),
                                vec3(bvhTriangleAt(IBL_BVH_ARG 3 * k + 2)));
        if (r.x > 0.0f && r.x < hit.t && bvhCovers(IBL_BVH_ARG k, r.y, r.z, origin, dir)) {
          hit.found = true;
          hit.t = r.x;
          hit.triangle = k;
          hit.u = r.y;
          hit.v = r.z;
          if (anyHit) return hit;
        }
      }
    } else {
      float tl = bvhBoxEntry(IBL_BVH_ARG int(a), origin, invDir, hit.t);
      float tr = bvhBoxEntry(IBL_BVH_ARG int(b), origin, invDir, hit.t);
      if (tl >= 0.0f && tr >= 0.0f) {
        next = tl <= tr ? int(a) : int(b);
        if (top < 64) stack[top++] = tl <= tr ? int(b) : int(a);
      } else if (tl >= 0.0f) {
        next = int(a);
      } else if (tr >= 0.0f) {
        next = int(b);
      }
    }
    // Otherwise the deferred farther children, skipping those now beyond the nearest hit.
    while (next < 0 && top > 0) {
      int c = stack[--top];
      if (bvhBoxEntry(IBL_BVH_ARG c, origin, invDir, hit.t) >= 0.0f) next = c;
    }
    node = next;
  }
  return hit;
}

IBL_END

#endif
