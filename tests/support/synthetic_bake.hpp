#pragma once
// Bakes made by hand for the shading rules' tests (tests/shared/test_split_sum.cpp,
// tests/shared/test_material.cpp): each map reads back a known function.
#include <functional>

#include <glm/geometric.hpp>

#include "ibl/bake/bake.hpp"
#include "support/helpers.hpp"

namespace ibl::test {

// A bake made by hand, so that each map reads back a known function: level m of the specular
// chain holds specular(m, d), the irradiance cube holds irradiance(d), the DFG table is the
// constant (A, B, diffuse).
struct SyntheticBake {
  BakeResult bake;
  BakeOptions options;
};
inline SyntheticBake syntheticBake(int levels,
                                   const std::function<glm::vec3(int, glm::vec3)>& specular,
                                   const RadianceFn& irradiance, glm::vec3 dfg, int size = 128) {
  SyntheticBake s;
  s.bake.specular = CubeMap(size, levels);
  for (int m = 0; m < levels; ++m)
    for (int f = 0; f < kFaceCount; ++f) {
      Image& face = s.bake.specular.levels[m][f];
      for (int y = 0; y < face.height; ++y)
        for (int x = 0; x < face.width; ++x)
          face.at(x, y) = specular(m, texelDirection(f, x, y, face.width));
    }
  s.bake.irradiance = cubeFromFunction(64, irradiance);
  s.bake.source = cubeFromFunction(8, [](glm::vec3) { return glm::vec3(0.0f); });
  s.bake.dfg = Image(8, 8, dfg);
  s.bake.sh = {};
  s.options.specular.size = size;
  s.options.specular.levels = levels;
  return s;
}

// A direction stored as radiance d + 2 (all components positive), read back.
inline glm::vec3 decodeDirection(glm::vec3 c) {
  return glm::normalize(c - glm::vec3(2.0f));
}

}  // namespace ibl::test
