#pragma once
// Materials that transmit, shared by the tests and the benches.
#include <glm/vec3.hpp>

#include "ibl/render/scene.hpp"

namespace ibl::test {

// Glass of base color c and perceptual roughness r that lets all of its light below the
// specular layer through (KHR_materials_transmission 1): a thin wall unless given a thickness.
inline Material transmissiveGlass(glm::vec3 c, float r = 0.0f) {
  Material m;
  m.baseColor = c;
  m.metallic = 0.0f;
  m.roughness = r;
  m.transmission = 1.0f;
  return m;
}

}  // namespace ibl::test
