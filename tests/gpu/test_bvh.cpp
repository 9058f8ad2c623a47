// The device path tracer's BVH (src/gpu/bvh.hpp, built by Embree's generic builder) and its
// traversal (ibl/shared/bvh.h, run here as C++) against Embree's own intersection of the same
// triangles (the renderer's RayTracer): the same nearest hits, the same occlusion, a well formed
// tree, and hits an alpha test rejects passed through.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "../../src/gpu/bvh.hpp"
#include "../../src/render/ray_tracer.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/shared/bvh.h"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// The scene's meshes only, every material opaque (Embree's alpha filters off): what the BVH
// holds, as the RayTracer sees it.
Scene meshesOnly(Scene s) {
  s.spheres.clear();
  for (Material& m : s.materials) m.alphaMode = AlphaMode::Opaque;
  return s;
}

// The sphere grid with its spheres as triangles.
Scene tessellatedSphereGrid() {
  Scene s = makeSphereGrid(glm::vec3(0.8f));
  for (const Sphere& sphere : s.spheres) {
    Mesh m = tessellateSphere(sphere, 24);
    m.material = sphere.material;
    s.meshes.push_back(std::move(m));
  }
  return meshesOnly(std::move(s));
}

std::uint32_t bitsOf(float f) {
  return std::bit_cast<std::uint32_t>(f);
}
std::uint32_t meshOf(const gpu::Bvh& bvh, int triangle) {
  return bitsOf(bvh.triangles[3 * static_cast<std::size_t>(triangle)].w);
}
std::uint32_t primitiveOf(const gpu::Bvh& bvh, int triangle) {
  return bitsOf(bvh.triangles[3 * static_cast<std::size_t>(triangle) + 1].w);
}

struct TestRay {
  glm::vec3 origin, dir;
};

// Rays from around and inside the scene's bounds: half in uniform directions, half aimed at a
// point inside the bounds.
std::vector<TestRay> randomRays(const Scene& scene, int count, unsigned seed) {
  const auto [lo, hi] = scene.bounds();
  const glm::vec3 center = 0.5f * (lo + hi), extent = hi - lo;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const auto inBox = [&](float scale) {
    return center + scale * (glm::vec3(unit(rng), unit(rng), unit(rng)) - 0.5f) * extent;
  };
  std::vector<TestRay> rays;
  for (int i = 0; i < count; ++i) {
    TestRay r;
    r.origin = inBox(1.5f);
    if (i % 2 == 0) {
      const float z = 2.0f * unit(rng) - 1.0f, phi = 2.0f * shared::kPi * unit(rng);
      const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
      r.dir = glm::vec3(s * std::cos(phi), s * std::sin(phi), z);
    } else {
      r.dir = glm::normalize(inBox(1.0f) - r.origin);
    }
    rays.push_back(r);
  }
  return rays;
}

// Whether a hit lies within 1e-4 (barycentric) of its triangle's edges: there the two
// intersectors may pick either neighbor, or (not watertight) neither.
bool grazes(float u, float v) {
  return std::min({u, v, 1.0f - u - v}) < 1e-4f;
}

// Whether the point the hit names on its triangle is the ray's at distance t.
bool onItsTriangle(const gpu::Bvh& bvh, const shared::BvhHit& h, const TestRay& r) {
  const std::size_t k = 3 * static_cast<std::size_t>(h.triangle);
  const glm::vec3 p = (1.0f - h.u - h.v) * glm::vec3(bvh.triangles[k]) +
                      h.u * glm::vec3(bvh.triangles[k + 1]) + h.v * glm::vec3(bvh.triangles[k + 2]);
  return h.u >= 0.0f && h.v >= 0.0f && h.u + h.v <= 1.0f &&
         glm::distance(p, r.origin + h.t * r.dir) <= 1e-4f * (1.0f + h.t);
}

// Counts over a batch of rays; `mismatches` holds the first few descriptions.
struct EmbreeComparison {
  int rays = 0, hits = 0, grazing = 0, ties = 0, occluded = 0;
  std::vector<std::string> mismatches;
  int mismatchCount = 0;
  void mismatch(const std::string& what) {
    if (++mismatchCount <= 5) mismatches.push_back(what);
  }
};

std::string describe(const TestRay& r, float tMax) {
  return "ray (" + std::to_string(r.origin.x) + ", " + std::to_string(r.origin.y) + ", " +
         std::to_string(r.origin.z) + ") dir (" + std::to_string(r.dir.x) + ", " +
         std::to_string(r.dir.y) + ", " + std::to_string(r.dir.z) + ") tMax " +
         std::to_string(tMax);
}

// Nearest hits (every third ray with a finite tMax) and any-hit occlusion (tMax around the
// nearest hit) of `view` over `bvh`, against Embree over `reference`; `meshMap` maps the BVH's
// mesh ids to the reference scene's.
EmbreeComparison compareWithEmbree(const gpu::Bvh& bvh, const shared::BvhView& view,
                                   const Scene& reference, const std::vector<TestRay>& rays,
                                   const std::vector<int>& meshMap) {
  const RayTracer tracer(reference);
  EmbreeComparison c;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const TestRay& r = rays[i];
    const RayTracer::Hit e = tracer.intersect(Ray{r.origin, r.dir});
    ++c.rays;
    // Closest hit.
    const float tMax = i % 3 == 0 ? (e.found ? e.t : 10.0f) * (0.5f + unit(rng)) : INFINITY;
    const bool expected = e.found && e.t < tMax;
    const shared::BvhHit h = shared::bvhIntersect(view, r.origin, r.dir, tMax, false);
    if ((e.found && (grazes(e.u, e.v) || std::abs(e.t - tMax) < 1e-3f * e.t)) ||
        (h.found && grazes(h.u, h.v))) {
      ++c.grazing;
      continue;
    }
    c.hits += expected;
    if (h.found != expected) {
      c.mismatch(describe(r, tMax) + ": found " + std::to_string(h.found) + ", Embree " +
                 std::to_string(expected));
    } else if (expected) {
      const int mesh = meshMap.at(meshOf(bvh, h.triangle));
      const bool same =
          mesh == static_cast<int>(e.geometry) && primitiveOf(bvh, h.triangle) == e.primitive;
      // Coplanar overlapping triangles (the room's rug on its floor) tie: either is right.
      if (!same && std::abs(h.t - e.t) <= 1e-5f * e.t && onItsTriangle(bvh, h, r))
        ++c.ties;
      else if (!same || std::abs(h.t - e.t) > 1e-4f * e.t || std::abs(h.u - e.u) > 1e-3f ||
               std::abs(h.v - e.v) > 1e-3f)
        c.mismatch(describe(r, tMax) + ": mesh " + std::to_string(mesh) + " primitive " +
                   std::to_string(primitiveOf(bvh, h.triangle)) + " t " + std::to_string(h.t) +
                   " uv " + std::to_string(h.u) + " " + std::to_string(h.v) + "; Embree mesh " +
                   std::to_string(e.geometry) + " primitive " + std::to_string(e.primitive) +
                   " t " + std::to_string(e.t) + " uv " + std::to_string(e.u) + " " +
                   std::to_string(e.v));
    }
    // Any hit, before a distance around the nearest hit's.
    const float tAny = (e.found ? e.t : 10.0f) * (0.5f + unit(rng));
    if (e.found && std::abs(e.t - tAny) < 1e-3f * e.t) continue;
    const bool occluded = tracer.occluded(r.origin, r.dir, tAny);
    const shared::BvhHit a = shared::bvhIntersect(view, r.origin, r.dir, tAny, true);
    c.occluded += occluded;
    if (a.found != occluded) {
      c.mismatch(describe(r, tAny) + ": any hit " + std::to_string(a.found) + ", Embree occluded " +
                 std::to_string(occluded));
    } else if (a.found) {
      // The hit it reports is one: on its triangle, on the ray, before tAny.
      if (!(a.t > 0.0f && a.t < tAny) || !onItsTriangle(bvh, a, r))
        c.mismatch(describe(r, tAny) + ": any hit off its triangle or range");
    }
  }
  return c;
}

void expectAgreement(const EmbreeComparison& c) {
  EXPECT_EQ(c.mismatchCount, 0);
  for (const std::string& m : c.mismatches) ADD_FAILURE() << m;
  EXPECT_LT(c.grazing, c.rays / 100) << "rays near edges, left out";
  EXPECT_LT(c.ties, c.rays / 100) << "hits on coplanar triangles, either taken";
  EXPECT_GT(c.hits, c.rays / 5) << "too few hits to compare";
  EXPECT_GT(c.occluded, c.rays / 5);
  EXPECT_LT(c.occluded, c.rays - c.rays / 10);
}

std::vector<int> identityMap(const Scene& s) {
  std::vector<int> map(s.meshes.size());
  for (std::size_t i = 0; i < map.size(); ++i) map[i] = static_cast<int>(i);
  return map;
}

// Walks the tree from the root: every node reached once, binary, bounds containing the
// children's and the leaves' triangles, leaves of 1 to 4 triangles covering the triangle array
// once, and the triangles the scene's (each mesh's each finite triangle exactly once).
void expectWellFormed(const gpu::Bvh& bvh, const Scene& scene) {
  ASSERT_EQ(bvh.nodes.size() % 2, 0u);
  ASSERT_EQ(bvh.triangles.size() % 3, 0u);
  const std::size_t nodeCount = bvh.nodes.size() / 2, triangleCount = bvh.triangles.size() / 3;
  std::vector<int> nodeSeen(nodeCount, 0), triangleSeen(triangleCount, 0);
  std::vector<std::pair<std::uint32_t, int>> stack = {{0u, 0}};
  int maxDepth = 0, errors = 0;
  const auto contains = [](glm::vec3 lo, glm::vec3 hi, glm::vec3 p) {
    return glm::all(glm::lessThanEqual(lo, p)) && glm::all(glm::lessThanEqual(p, hi));
  };
  while (!stack.empty()) {
    const auto [n, depth] = stack.back();
    stack.pop_back();
    ASSERT_LT(n, nodeCount);
    ++nodeSeen[n];
    maxDepth = std::max(maxDepth, depth);
    const glm::vec3 lo(bvh.nodes[2 * n]), hi(bvh.nodes[2 * n + 1]);
    const std::uint32_t a = bitsOf(bvh.nodes[2 * n].w), b = bitsOf(bvh.nodes[2 * n + 1].w);
    if (b & 0x80000000u) {
      const std::uint32_t count = b & 0x7fffffffu;
      EXPECT_GE(count, 1u);
      EXPECT_LE(count, 4u);
      ASSERT_LE(a + count, triangleCount);
      for (std::uint32_t t = a; t < a + count; ++t) {
        ++triangleSeen[t];
        for (int k = 0; k < 3; ++k)
          errors += !contains(lo, hi, glm::vec3(bvh.triangles[3 * t + k]));
      }
    } else {
      for (std::uint32_t child : {a, b}) {
        ASSERT_LT(child, nodeCount);
        errors += !contains(lo, hi, glm::vec3(bvh.nodes[2 * child])) ||
                  !contains(lo, hi, glm::vec3(bvh.nodes[2 * child + 1]));
        stack.push_back({child, depth + 1});
      }
    }
  }
  EXPECT_EQ(errors, 0) << "bounds not containing their children or triangles";
  EXPECT_LE(maxDepth, 32);
  EXPECT_EQ(std::count(nodeSeen.begin(), nodeSeen.end(), 1), static_cast<long>(nodeCount));
  EXPECT_EQ(std::count(triangleSeen.begin(), triangleSeen.end(), 1),
            static_cast<long>(triangleCount));
  // The triangles are the scene's, each once, with its vertices.
  std::set<std::pair<std::uint32_t, std::uint32_t>> ids;
  int wrongVertices = 0;
  for (std::size_t t = 0; t < triangleCount; ++t) {
    const std::uint32_t m = meshOf(bvh, static_cast<int>(t)),
                        p = primitiveOf(bvh, static_cast<int>(t));
    ASSERT_LT(m, scene.meshes.size());
    ASSERT_LT(3 * p + 2, scene.meshes[m].indices.size());
    ids.insert({m, p});
    for (int k = 0; k < 3; ++k)
      wrongVertices += glm::vec3(bvh.triangles[3 * t + k]) !=
                       scene.meshes[m].positions[scene.meshes[m].indices[3 * p + k]];
  }
  std::size_t sceneTriangles = 0;
  for (const Mesh& m : scene.meshes) sceneTriangles += m.indices.size() / 3;
  EXPECT_EQ(triangleCount, sceneTriangles);
  EXPECT_EQ(ids.size(), sceneTriangles) << "a triangle missing or repeated";
  EXPECT_EQ(wrongVertices, 0);
}

Scene room() {
  return meshesOnly(loadGltf((dataDir() / "scenes" / "room.gltf").string()));
}

}  // namespace

TEST(Bvh, SphereGridHitsEqualEmbree) {
  const Scene scene = tessellatedSphereGrid();
  const gpu::Bvh bvh = gpu::buildBvh(scene);
  expectAgreement(
      compareWithEmbree(bvh, bvh.view(), scene, randomRays(scene, 10000, 1), identityMap(scene)));
}

TEST(Bvh, GltfHitsEqualEmbree) {
  for (const std::string& path : {(dataDir() / "scenes" / "room.gltf").string(),
                                  (dataDir() / "models" / "bunny.glb").string()}) {
    SCOPED_TRACE(path);
    const Scene scene = meshesOnly(loadGltf(path));
    const gpu::Bvh bvh = gpu::buildBvh(scene);
    expectAgreement(
        compareWithEmbree(bvh, bvh.view(), scene, randomRays(scene, 10000, 2), identityMap(scene)));
  }
}

TEST(Bvh, TreeIsWellFormed) {
  for (const Scene& scene : {tessellatedSphereGrid(), room(),
                             meshesOnly(loadGltf((dataDir() / "models" / "bunny.glb").string()))}) {
    const gpu::Bvh bvh = gpu::buildBvh(scene);
    EXPECT_GT(bvh.nodes.size(), 2u);
    expectWellFormed(bvh, scene);
  }
}

TEST(Bvh, EmptySceneIsOneEmptyLeaf) {
  Scene scene = makeSphereGrid(glm::vec3(0.8f));  // spheres only: no triangles
  const gpu::Bvh bvh = gpu::buildBvh(scene);
  ASSERT_EQ(bvh.nodes.size(), 2u);
  EXPECT_TRUE(bvh.triangles.empty());
  EXPECT_EQ(bitsOf(bvh.nodes[1].w), 0x80000000u);
  EXPECT_FALSE(shared::bvhIntersect(bvh.view(), glm::vec3(0.0f, 0.0f, 5.0f),
                                    glm::vec3(0.0f, 0.0f, -1.0f), INFINITY, false)
                   .found);
}

// An alpha test rejecting every triangle of one mesh (the room's most hit piece of furniture)
// makes it invisible: the rays hit what is behind it, as Embree over the room without it does.
TEST(Bvh, RejectedHitsPassThrough) {
  const Scene scene = room();
  const gpu::Bvh bvh = gpu::buildBvh(scene);
  const std::vector<TestRay> rays = randomRays(scene, 10000, 3);
  // The most hit mesh whose material is neither the floor's nor the walls' (meshes 0 and 1).
  std::vector<int> hitsPerMesh(scene.meshes.size(), 0);
  for (const TestRay& r : rays) {
    const shared::BvhHit h = shared::bvhIntersect(bvh.view(), r.origin, r.dir, INFINITY, false);
    if (h.found) ++hitsPerMesh[meshOf(bvh, h.triangle)];
  }
  int rejected = -1;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    if (scene.meshes[m].material > 1 && (rejected < 0 || hitsPerMesh[m] > hitsPerMesh[rejected]))
      rejected = static_cast<int>(m);
  ASSERT_GE(rejected, 0);
  EXPECT_GT(hitsPerMesh[rejected], 100);

  struct Rejection {
    const gpu::Bvh* bvh;
    std::uint32_t mesh;
    mutable int calls;
  } rejection{&bvh, static_cast<std::uint32_t>(rejected), 0};
  const auto covers = [](const void* user, int triangle, float, float, glm::vec3, glm::vec3) {
    const auto* r = static_cast<const Rejection*>(user);
    ++r->calls;
    return meshOf(*r->bvh, triangle) != r->mesh;
  };
  Scene without = scene;
  without.meshes.erase(without.meshes.begin() + rejected);
  std::vector<int> meshMap = identityMap(scene);
  for (int& m : meshMap) m = m > rejected ? m - 1 : (m == rejected ? -1 : m);
  expectAgreement(compareWithEmbree(bvh, bvh.view(covers, &rejection), without, rays, meshMap));
  EXPECT_GT(rejection.calls, 0);

  // And those rays do hit something behind it.
  int behind = 0;
  for (const TestRay& r : rays) {
    const shared::BvhHit full = shared::bvhIntersect(bvh.view(), r.origin, r.dir, INFINITY, false);
    if (!full.found || meshOf(bvh, full.triangle) != rejection.mesh) continue;
    const shared::BvhHit h =
        shared::bvhIntersect(bvh.view(covers, &rejection), r.origin, r.dir, INFINITY, false);
    behind += h.found && h.t > full.t;
  }
  EXPECT_GT(behind, 50);
}
