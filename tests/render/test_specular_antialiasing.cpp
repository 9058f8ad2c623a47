// Specular antialiasing in the CPU's split sum (renderRays with
// RenderOptions::specularAntialiasing): one sample per pixel of a glossy sphere under a bumpy
// normal map comes nearer the same render supersampled (64 jittered samples per pixel, without
// the widening: the reference that resolves the map's detail).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "support/bumpy_sphere.hpp"

namespace ibl {
namespace {

using test::bumpy::bumpySphereScene;
using test::bumpy::relativeError;
using test::bumpy::skyBake;

TEST(SpecularAntialiasingRender, OneSampleComesNearerTheSupersampledRender) {
  const test::bumpy::SkyBake& b = skyBake();
  const Camera camera = test::bumpy::sphereCamera96();
  // Bumps 4 and 1/2 pixels wide at the sphere's center: resolved, and finer than a pixel.
  for (int bumps : {48, 384})
    for (float roughness : {0.02f, 0.1f, 0.25f}) {
      const Scene scene = bumpySphereScene(roughness, bumps);
      RenderOptions reference = test::bumpy::oneSample(false);
      reference.spp = 64;
      const RenderResult truth = renderScene(scene, camera, b.result, b.options, reference);
      const RenderResult plain =
          renderScene(scene, camera, b.result, b.options, test::bumpy::oneSample(false));
      const RenderResult filtered =
          renderScene(scene, camera, b.result, b.options, test::bumpy::oneSample(true));
      const double before = relativeError(plain, truth), after = relativeError(filtered, truth);
      std::printf("bumps %d roughness %.2f: relative error %.4f without, %.4f with\n", bumps,
                  roughness, before, after);
      if (bumps == 384 && roughness == 0.25f) {
        test::bumpy::keep(truth, "supersampled");
        test::bumpy::keep(plain, "cpu_plain");
        test::bumpy::keep(filtered, "cpu_antialiased");
      }
      EXPECT_LT(after, (bumps > 96 ? 0.8 : 1.0) * before) << bumps << " " << roughness;
    }
}

}  // namespace
}  // namespace ibl
