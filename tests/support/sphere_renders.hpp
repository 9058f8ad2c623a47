#pragma once
// What the render tests share: a bake of an analytic environment, an orthographic view of the
// unit sphere, and the mask of pixels fully on the model.
#include <vector>

#include "ibl/bake/bake.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/renderer.hpp"
#include "support/helpers.hpp"

namespace ibl::test {

struct Baked {
  BakeOptions options;
  BakeResult result;
};

// The environment f, baked at `size` (with the sheen chain if asked, its table integrated with
// `visibility`).
inline Baked bakeOf(const RadianceFn& f, int size = 64, bool sheen = false,
                    SheenVisibility visibility = SheenVisibility::Charlie) {
  Baked b;
  b.options.specular.size = size;
  b.options.irradianceSize = 16;
  b.options.dfgSize = 64;
  b.options.dfgSamples = 1024;
  b.options.sheen = sheen;
  b.options.sheenVisibility = visibility;
  b.result = bakeEnvironment(equirectEnvironment(equirectFromFunction(512, f)), b.options);
  return b;
}

// An orthographic view of the unit sphere from +Z, n pixels wide and `height` high (n: square):
// pixel (n/2, n/2) looks at its center; with height 1 the middle row.
inline Camera sphereCamera(int n, int height = 0) {
  Camera c;
  c.perspective = false;
  c.orthoWidth = 2.0f;
  c.from = glm::vec3(0, 0, 5);
  c.width = n;
  c.height = height > 0 ? height : n;
  return c;
}

// Pixels fully on the model in both renders (silhouette pixels mix in the background).
inline std::vector<float> interiorMask(const RenderResult& a, const RenderResult& b) {
  std::vector<float> m(a.alpha.size());
  for (std::size_t i = 0; i < m.size(); ++i)
    m[i] = a.alpha[i] == 1.0f && b.alpha[i] == 1.0f ? 1.0f : 0.0f;
  return m;
}

}  // namespace ibl::test
