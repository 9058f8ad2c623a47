#include "mesh_tangents.hpp"

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

namespace ibl {

std::vector<glm::vec3> generateNormals(const Mesh& m) {
  std::vector<glm::vec3> n(m.positions.size(), glm::vec3(0.0f));
  for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
    const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                    c = m.positions[m.indices[i + 2]];
    const glm::vec3 face = glm::cross(b - a, c - a);
    for (int k = 0; k < 3; ++k) n[m.indices[i + k]] += face;
  }
  for (auto& v : n) v = glm::length(v) > 0.0f ? glm::normalize(v) : glm::vec3(0, 0, 1);
  return n;
}

std::vector<glm::vec4> generateTangents(const Mesh& m, const std::vector<glm::vec2>& uvs) {
  std::vector<glm::vec3> tan(m.positions.size(), glm::vec3(0.0f)),
      bit(m.positions.size(), glm::vec3(0.0f));
  for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
    const std::uint32_t i0 = m.indices[i], i1 = m.indices[i + 1], i2 = m.indices[i + 2];
    const glm::vec3 e1 = m.positions[i1] - m.positions[i0], e2 = m.positions[i2] - m.positions[i0];
    const glm::vec2 d1 = uvs[i1] - uvs[i0], d2 = uvs[i2] - uvs[i0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-20f) continue;
    const float r = 1.0f / det;
    const glm::vec3 t = (e1 * d2.y - e2 * d1.y) * r, b = (e2 * d1.x - e1 * d2.x) * r;
    for (std::uint32_t k : {i0, i1, i2}) {
      tan[k] += t;
      bit[k] += b;
    }
  }
  std::vector<glm::vec4> out(m.positions.size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    const glm::vec3 n = m.normals[k];
    glm::vec3 t = tan[k] - n * glm::dot(n, tan[k]);
    if (glm::length(t) < 1e-12f)
      t = std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0))
                               : glm::cross(n, glm::vec3(0, 1, 0));
    t = glm::normalize(t);
    out[k] = glm::vec4(t, glm::dot(glm::cross(n, t), bit[k]) < 0.0f ? -1.0f : 1.0f);
  }
  return out;
}

}  // namespace ibl
