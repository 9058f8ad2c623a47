#pragma once
// A box room for the probe tests and benchmark: six inward-facing walls, each tiled n x n with
// two alternating materials (so that where a reflection lands on a wall shows), an optional
// window (tiles left out of the +X wall) and objects added by the caller.
#include <array>

#include <glm/geometric.hpp>

#include "ibl/render/scene.hpp"

namespace ibl::test {

// A quad (corner, corner + u, corner + u + v, corner + v) whose normal faces `inside`.
inline void addQuad(Scene& scene, glm::vec3 corner, glm::vec3 u, glm::vec3 v, int material,
                    glm::vec3 inside) {
  Mesh m;
  glm::vec3 n = glm::normalize(glm::cross(u, v));
  const bool flip = glm::dot(n, inside - (corner + 0.5f * (u + v))) < 0.0f;
  if (flip) n = -n;
  m.positions = {corner, corner + u, corner + u + v, corner + v};
  m.normals.assign(4, n);
  m.indices = flip ? std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2}
                   : std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3};
  m.material = material;
  scene.meshes.push_back(std::move(m));
}

struct RoomDescription {
  glm::vec3 lo{-2.0f, 0.0f, -2.0f}, hi{2.0f, 3.0f, 2.0f};
  int tiles = 4;
  // Per wall (-X, +X, -Y floor, +Y ceiling, -Z, +Z): the two materials of its tiles.
  std::array<std::array<Material, 2>, 6> walls;
  bool window = false;  // leave the middle tiles of the +X wall out
};

inline Scene makeRoom(const RoomDescription& room) {
  Scene scene;
  const glm::vec3 center = 0.5f * (room.lo + room.hi), size = room.hi - room.lo;
  for (int wall = 0; wall < 6; ++wall) {
    const int axis = wall / 2;
    const bool high = wall % 2 == 1;
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    glm::vec3 u(0.0f), v(0.0f), origin = room.lo;
    if (high) origin[axis] = room.hi[axis];
    u[a] = size[a] / static_cast<float>(room.tiles);
    v[b] = size[b] / static_cast<float>(room.tiles);
    const int first = static_cast<int>(scene.materials.size());
    scene.materials.push_back(room.walls[wall][0]);
    scene.materials.push_back(room.walls[wall][1]);
    for (int i = 0; i < room.tiles; ++i)
      for (int j = 0; j < room.tiles; ++j) {
        const bool middle = i > 0 && i < room.tiles - 1 && j > 0 && j < room.tiles - 1;
        if (room.window && wall == 1 && middle) continue;
        addQuad(scene, origin + static_cast<float>(i) * u + static_cast<float>(j) * v, u, v,
                first + (i + j) % 2, center);
      }
  }
  return scene;
}

}  // namespace ibl::test
