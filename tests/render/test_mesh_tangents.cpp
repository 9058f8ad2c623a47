// Normal and tangent generation (src/render/mesh_tangents.cpp) against closed forms: a flat
// quad's normal and its tangent along +U, a sphere's normals along its radii, a mirrored UV set's
// handedness.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "../../src/render/mesh_tangents.hpp"

using namespace ibl;

namespace {

// A unit square in the XY plane, facing +Z (counter-clockwise seen from +Z), UVs (x, y).
Mesh flatQuad() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

// A unit sphere of `rings` latitude bands and `segments` longitude bands, its triangles wound
// counter-clockwise seen from outside; one vertex at each pole.
Mesh sphere(int rings, int segments) {
  Mesh m;
  m.positions.push_back({0, 0, 1});
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double theta = std::numbers::pi * i / rings, phi = 2 * std::numbers::pi * j / segments;
      m.positions.push_back(glm::vec3(std::sin(theta) * std::cos(phi),
                                      std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  m.positions.push_back({0, 0, -1});
  const auto at = [&](int ring, int j) {  // ring 1 .. rings - 1
    return static_cast<std::uint32_t>(1 + (ring - 1) * segments + (j % segments));
  };
  const auto south = static_cast<std::uint32_t>(m.positions.size() - 1);
  for (int j = 0; j < segments; ++j) {
    m.indices.insert(m.indices.end(), {0, at(1, j), at(1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i)
      m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j),
                                         at(i + 1, j + 1), at(i, j + 1)});
    m.indices.insert(m.indices.end(), {at(rings - 1, j), south, at(rings - 1, j + 1)});
  }
  return m;
}

}  // namespace

// The quad's normal is +Z at every vertex; its tangent is dP/du = +X, and its bitangent
// dP/dv = +Y = cross(N, T): handedness +1.
TEST(MeshTangents, FlatQuadHasItsFaceNormalAndTangentAlongU) {
  Mesh m = flatQuad();
  m.normals = generateNormals(m);
  ASSERT_EQ(m.normals.size(), 4u);
  for (const glm::vec3& n : m.normals) EXPECT_LT(glm::distance(n, glm::vec3(0, 0, 1)), 1e-6f);
  const std::vector<glm::vec4> t = generateTangents(m, m.uvs);
  ASSERT_EQ(t.size(), 4u);
  for (const glm::vec4& v : t) EXPECT_LT(glm::distance(v, glm::vec4(1, 0, 0, 1)), 1e-6f);
}

// The UVs mirrored in u (u = 1 - x): dP/du = -X, dP/dv = +Y = -cross(N, T): handedness -1.
TEST(MeshTangents, MirroredUvsGiveNegativeHandedness) {
  Mesh m = flatQuad();
  for (glm::vec2& uv : m.uvs) uv.x = 1.0f - uv.x;
  m.normals = generateNormals(m);
  for (const glm::vec4& v : generateTangents(m, m.uvs))
    EXPECT_LT(glm::distance(v, glm::vec4(-1, 0, 0, -1)), 1e-6f);
}

// A sphere's area-weighted normals point along its radii: exactly at the poles (by symmetry),
// elsewhere within the tessellation's error, a fraction of the angle between rings (pi / 48).
TEST(MeshTangents, SphereNormalsAreItsRadialDirections) {
  const Mesh m = sphere(48, 96);  // rings pi / 48 apart
  const std::vector<glm::vec3> n = generateNormals(m);
  ASSERT_EQ(n.size(), m.positions.size());
  float worst = 0.0f;
  for (std::size_t k = 0; k < n.size(); ++k) {
    EXPECT_NEAR(glm::length(n[k]), 1.0f, 1e-5f) << k;
    worst = std::max(worst, glm::distance(n[k], glm::normalize(m.positions[k])));
  }
  EXPECT_LT(glm::distance(n.front(), glm::vec3(0, 0, 1)), 1e-5f);
  EXPECT_LT(glm::distance(n.back(), glm::vec3(0, 0, -1)), 1e-5f);
  // First order in the spacing: largest on the rings next to the poles, where the fans meet the
  // bands (about a sixth of it there).
  EXPECT_LT(worst, 0.25f * std::numbers::pi_v<float> / 48);
}

// Tangents are unit and orthogonal to the normal they were made for, even where the UVs'
// derivative is not (a tilted normal); a vertex with degenerate UVs gets some unit tangent
// orthogonal to its normal; a vertex no triangle uses gets the normal +Z.
TEST(MeshTangents, TangentsAreOrthogonalizedAndDefined) {
  Mesh m = flatQuad();
  m.normals = std::vector<glm::vec3>(4, glm::normalize(glm::vec3(1, 0, 1)));
  for (const glm::vec4& t : generateTangents(m, m.uvs)) {
    EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(glm::vec3(t), m.normals[0]), 0.0f, 1e-6f);
    EXPECT_LT(glm::distance(glm::vec3(t), glm::normalize(glm::vec3(1, 0, -1))), 1e-6f);
  }
  Mesh flat = flatQuad();
  flat.uvs = std::vector<glm::vec2>(4, glm::vec2(0.5f));  // every triangle degenerate in UV
  flat.positions.push_back({5, 5, 5});                    // a vertex no triangle uses
  flat.uvs.push_back({0, 0});
  flat.normals = generateNormals(flat);
  EXPECT_EQ(flat.normals.back(), glm::vec3(0, 0, 1));
  for (const glm::vec4& t : generateTangents(flat, flat.uvs)) {
    EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(glm::vec3(t), glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  }
}
