#pragma once
// A small bake of a uniform white environment, for renders whose light is known.
#include "ibl/bake/bake.hpp"
#include "support/helpers.hpp"

namespace ibl::test {

inline BakeResult smallBake(BakeOptions& options) {
  options.specular.size = 16;
  options.irradianceSize = 8;
  options.dfgSize = 16;
  options.dfgSamples = 64;
  return bakeEnvironment(
      equirectEnvironment(equirectFromFunction(64, [](glm::vec3) { return glm::vec3(1.0f); })),
      options);
}

}  // namespace ibl::test
