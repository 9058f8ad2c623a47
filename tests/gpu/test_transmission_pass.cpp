// The viewer's opaque frame behind transmissive surfaces (src/gpu/transmission_pass.cpp): drawn,
// halved by linear blits and read at the refracted exit point as the CPU's split sum reads its own
// (ibl/render/transmission_frame.hpp). Like the other GPU tests, this fails without a Vulkan
// device.
#include <cstdio>

#include <gtest/gtest.h>

#include "ibl/gpu/viewer.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/viewer_comparison.hpp"

using namespace ibl;
using namespace ibl::test;
using namespace ibl::test::viewer;

namespace {

// The sphere grid of glass (a thickness of 0: thin walls), before a textured backdrop; with a
// volume, a pane of the same glass before the right half, placed by a node that scales its
// thickness 2.5 times.
Scene glassBeforeBackdrop(float thickness) {
  Material glass;
  glass.baseColor = glm::vec3(0.9f, 0.8f, 0.6f);
  glass.transmission = 1.0f;
  glass.thickness = thickness;
  Scene scene = makeSphereGrid(glass);
  scene.textures.push_back(gridTexture(230, false));
  Material backdrop;
  backdrop.metallic = 0.0f;
  backdrop.roughness = 0.7f;
  backdrop.baseColorTexture.index = 0;
  scene.materials.push_back(backdrop);
  Mesh quad;
  quad.positions = {
      {-9.0f, -4.0f, -3.0f}, {9.0f, -4.0f, -3.0f}, {9.0f, 4.0f, -3.0f}, {-9.0f, 4.0f, -3.0f}};
  quad.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
  quad.uvs = {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.material = static_cast<int>(scene.materials.size()) - 1;
  scene.meshes.push_back(quad);
  if (thickness > 0.0f) {
    Mesh pane = quad;
    pane.positions = {
        {1.0f, -3.0f, 2.0f}, {8.0f, -3.0f, 2.0f}, {8.0f, 3.0f, 2.0f}, {1.0f, 3.0f, 2.0f}};
    pane.uvs.clear();
    pane.material = 6;  // the first dielectric of the grid's lower row: roughness 0
    pane.thicknessScale = 2.5f;
    scene.meshes.push_back(pane);
  }
  return scene;
}

}  // namespace

// The opaque frame behind transmissive surfaces: the sphere grid as thin walls, then as solid
// glass (the refracted exit point) with a pane whose node scales its thickness, of roughness 0 to
// 1 (the chain's levels), before a textured backdrop: the viewer's frame, halved by linear blits
// and read through its trilinear sampler, against the CPU's.
TEST(TransmissionPass, FrameMatchesTheCpu) {
  for (float thickness : {0.0f, 1.5f}) {
    RenderOptions o;
    o.spp = 1;
    const Comparison c =
        renderBoth(glassBeforeBackdrop(thickness), lookingAt({0.0f, 0.0f, 16.0f}, 160, 80), o);
    std::printf("transmission frame, thickness %.1f: mean relative difference %.2e\n", thickness,
                c.meanRelative);
    EXPECT_LT(c.meanRelative, 4e-3) << "thickness " << thickness;
    EXPECT_LT(c.coverageMismatch, 5e-3) << "thickness " << thickness;
  }
}

// With all else a frame draws (screen-space reflections, whose lit frame reads the opaque frame
// too; ambient occlusion; 4 multisamples, resolved into the opaque frame), two frames in a row
// under the validation layer (the layouts of the images the passes share: any message fails the
// test), against the CPU's split sum of the same options.
TEST(TransmissionPass, DrawsWithTheScreenSpaceEffectsAndMultisamples) {
  const Scene scene = glassBeforeBackdrop(1.5f);
  const viewer::Baked& b = sunsetBake();
  RenderOptions o;
  o.spp = 4;
  o.screenReflections.enabled = true;
  o.screenAmbientOcclusion.enabled = true;
  const Camera camera = lookingAt({0.0f, 0.0f, 16.0f}, 160, 80);
  gpu::SceneRenderer device(graphicsContext(), scene, b.bake, b.options);
  device.render(camera, o);
  const Comparison c =
      compare(device.render(camera, o), renderScene(scene, camera, b.bake, b.options, o));
  std::printf("with reflections, occlusion and 4 samples: mean relative difference %.2e\n",
              c.meanRelative);
  EXPECT_LT(c.meanRelative, 0.02);
}
