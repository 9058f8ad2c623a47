#pragma once
// A local probe captured in a scene and baked in memory, as `ibl probe` does on disk (a small
// DFG table: the tests using it look at the cube maps).
#include "ibl/bake/bake.hpp"
#include "ibl/render/probe.hpp"

namespace ibl::test {

// Captures `scene` lit by the distant `env` at `placement.position` and bakes the capture.
inline LocalProbe captureAndBakeProbe(const Scene& scene, const BakeResult& env,
                                      const BakeOptions& envOptions,
                                      const ProbePlacement& placement,
                                      const CaptureOptions& capture) {
  const ProbeCapture c = captureProbe(scene, placement.position, env, envOptions, capture);
  BakeOptions options;
  options.specular.size = capture.size;
  options.dfgSamples = 64;
  return bakeProbe(c, placement, capture, options);
}

// A placement whose proxy is also its influence, without a fade.
inline ProbePlacement placementAt(glm::vec3 at, const ProbeVolume& proxy,
                                  const ProbeVolume& influence, float fade) {
  ProbePlacement p;
  p.position = at;
  p.hasProxy = true;
  p.proxy = proxy;
  p.influence = influence;
  p.fade = fade;
  return p;
}

}  // namespace ibl::test
