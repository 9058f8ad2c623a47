#include "bvh.hpp"

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>

#include <embree3/rtcore.h>

#include "ibl/core/error.hpp"

namespace ibl::gpu {

namespace {

constexpr unsigned kMaxLeafSize = 4;

// The temporary tree, in the builder's thread-local memory (freed with the RTCBVH).
struct BuildNode {
  bool leaf;
  // Inner nodes: the two children and their bounds.
  BuildNode* children[2];
  RTCBounds bounds[2];
  // Leaves: the triangles (mesh, primitive).
  unsigned count;
  unsigned mesh[kMaxLeafSize];
  unsigned primitive[kMaxLeafSize];
};

void* createNode(RTCThreadLocalAllocator allocator, unsigned childCount, void*) {
  if (childCount != 2) return nullptr;  // maxBranchingFactor 2
  auto* n = static_cast<BuildNode*>(
      rtcThreadLocalAlloc(allocator, sizeof(BuildNode), alignof(BuildNode)));
  n->leaf = false;
  n->children[0] = n->children[1] = nullptr;
  n->count = 0;
  return n;
}

void setNodeChildren(void* node, void** children, unsigned childCount, void*) {
  auto* n = static_cast<BuildNode*>(node);
  for (unsigned i = 0; i < childCount && i < 2; ++i)
    n->children[i] = static_cast<BuildNode*>(children[i]);
}

void setNodeBounds(void* node, const RTCBounds** bounds, unsigned childCount, void*) {
  auto* n = static_cast<BuildNode*>(node);
  for (unsigned i = 0; i < childCount && i < 2; ++i) n->bounds[i] = *bounds[i];
}

void* createLeaf(RTCThreadLocalAllocator allocator, const RTCBuildPrimitive* primitives,
                 std::size_t count, void*) {
  if (count > kMaxLeafSize) return nullptr;
  auto* n = static_cast<BuildNode*>(
      rtcThreadLocalAlloc(allocator, sizeof(BuildNode), alignof(BuildNode)));
  n->leaf = true;
  n->children[0] = n->children[1] = nullptr;
  n->count = static_cast<unsigned>(count);
  for (std::size_t i = 0; i < count; ++i) {
    n->mesh[i] = primitives[i].geomID;
    n->primitive[i] = primitives[i].primID;
  }
  return n;
}

float bitsOf(std::uint32_t u) {
  return std::bit_cast<float>(u);
}

// Appends node n (with bounds lo, hi) and below it, depth first; returns its index.
std::uint32_t flatten(const Scene& scene, const BuildNode& n, glm::vec3 lo, glm::vec3 hi,
                      Bvh& out) {
  const auto index = static_cast<std::uint32_t>(out.nodes.size() / 2);
  out.nodes.emplace_back(lo, 0.0f);
  out.nodes.emplace_back(hi, 0.0f);
  if (n.leaf) {
    const auto first = static_cast<std::uint32_t>(out.triangles.size() / 3);
    for (unsigned i = 0; i < n.count; ++i) {
      const Mesh& m = scene.meshes[n.mesh[i]];
      const std::uint32_t* t = &m.indices[3 * static_cast<std::size_t>(n.primitive[i])];
      out.triangles.emplace_back(m.positions[t[0]], bitsOf(n.mesh[i]));
      out.triangles.emplace_back(m.positions[t[1]], bitsOf(n.primitive[i]));
      out.triangles.emplace_back(m.positions[t[2]], 0.0f);
    }
    out.nodes[2 * index].w = bitsOf(first);
    out.nodes[2 * index + 1].w = bitsOf(0x80000000u | n.count);
    return index;
  }
  std::uint32_t child[2];
  for (int i = 0; i < 2; ++i) {
    const RTCBounds& b = n.bounds[i];
    child[i] = flatten(scene, *n.children[i], {b.lower_x, b.lower_y, b.lower_z},
                       {b.upper_x, b.upper_y, b.upper_z}, out);
  }
  out.nodes[2 * index].w = bitsOf(child[0]);
  out.nodes[2 * index + 1].w = bitsOf(child[1]);
  return index;
}

}  // namespace

Bvh buildBvh(const Scene& scene) {
  std::vector<RTCBuildPrimitive> primitives;
  glm::vec3 lo(FLT_MAX), hi(-FLT_MAX);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      glm::vec3 a(FLT_MAX), b(-FLT_MAX);
      bool finite = true;
      for (std::size_t k = 0; k < 3; ++k) {
        const glm::vec3 p = mesh.positions.at(mesh.indices[t + k]);
        finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
        a = glm::min(a, p);
        b = glm::max(b, p);
      }
      if (!finite) continue;
      lo = glm::min(lo, a);
      hi = glm::max(hi, b);
      RTCBuildPrimitive& p = primitives.emplace_back();
      p.lower_x = a.x;
      p.lower_y = a.y;
      p.lower_z = a.z;
      p.upper_x = b.x;
      p.upper_y = b.y;
      p.upper_z = b.z;
      p.geomID = static_cast<unsigned>(m);
      p.primID = static_cast<unsigned>(t / 3);
    }
  }
  Bvh out;
  if (primitives.empty()) {
    out.nodes = {glm::vec4(lo, bitsOf(0u)), glm::vec4(hi, bitsOf(0x80000000u))};
    return out;
  }

  // Released on every way out (the temporary tree lives in the RTCBVH's memory).
  struct Handles {
    RTCDevice device = rtcNewDevice(nullptr);
    RTCBVH bvh = device ? rtcNewBVH(device) : nullptr;
    ~Handles() {
      if (bvh) rtcReleaseBVH(bvh);
      if (device) rtcReleaseDevice(device);
    }
  } h;
  if (!h.device || !h.bvh) fail("embree", "cannot create a device");
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.byteSize = sizeof(args);
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
  args.maxBranchingFactor = 2;
  args.maxDepth = 32;  // bvhIntersect's stack holds 64
  args.minLeafSize = 1;
  args.maxLeafSize = kMaxLeafSize;
  args.bvh = h.bvh;
  args.primitives = primitives.data();
  args.primitiveCount = primitives.size();
  args.primitiveArrayCapacity = primitives.size();
  args.createNode = createNode;
  args.setNodeChildren = setNodeChildren;
  args.setNodeBounds = setNodeBounds;
  args.createLeaf = createLeaf;
  const auto* root = static_cast<const BuildNode*>(rtcBuildBVH(&args));
  if (!root || rtcGetDeviceError(h.device) != RTC_ERROR_NONE)
    fail("embree", "cannot build the BVH of the scene's triangles");
  out.nodes.reserve(4 * primitives.size());
  out.triangles.reserve(3 * primitives.size());
  flatten(scene, *root, lo, hi, out);
  return out;
}

}  // namespace ibl::gpu
