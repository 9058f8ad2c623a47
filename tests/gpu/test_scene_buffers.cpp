// The scene as the device's ray tracers read it (src/gpu/scene_buffers.cpp, read by
// shaders/render/scene_buffers.glsl): the offsets follow the layout the shader documents (meshes,
// then 4 vec4 per vertex, kMaterialRecordVec4s per material, 1 per texture, kLightRecordVec4s per
// light, 2 per sphere), and the records read back at them hold the scene's values.
#include <vector>

#include <gtest/gtest.h>

#include "../../src/gpu/scene_buffers.hpp"
#include "ibl/shared/light_record.h"
#include "ibl/shared/material.h"
#include "support/gpu_context.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

TEST(SceneBuffers, RecordsLieWhereTheShaderReadsThem) {
  Scene scene = makeSphereGrid(glm::vec3(0.8f), 3);
  Mesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.normals.assign(4, glm::vec3(0, 0, 1));
  quad.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0.25f, 0.5f, 0.75f, 0.4f}, {0, 0, 1, 1}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.material = 1;
  scene.meshes.push_back(quad);
  Light lamp;
  lamp.position = {0.0f, 2.0f, 0.0f};
  lamp.intensity = 100.0f;
  scene.lights = {lamp, lamp};
  const gpu::SceneBuffers b = gpu::uploadSceneBuffers(context(), scene);
  const auto lights = static_cast<unsigned>(scene.lights.size());
  const auto spheres = static_cast<unsigned>(scene.spheres.size());
  const auto materials = static_cast<unsigned>(scene.materials.size());
  EXPECT_EQ(b.counts, glm::uvec4(lights, spheres, 0u, 0u));
  const glm::uvec4 o = b.offsets, o2 = b.offsets2;
  EXPECT_EQ(o.x, 1u);  // one mesh record
  const auto vertex = static_cast<unsigned>(shared::kVertexRecordVec4s);
  EXPECT_EQ(o.y, o.x + 4u * vertex);                               // four vertices
  EXPECT_EQ(o.z, o.y + shared::kMaterialRecordVec4s * materials);  // the materials
  EXPECT_EQ(o.w, o.z);                                             // no textures
  EXPECT_EQ(o2.x, o.w + lights * shared::kLightRecordVec4s);       // the lights
  EXPECT_EQ(o2.y, o2.x + 2u * spheres);                            // the spheres, then no emitters
  const std::vector<glm::vec4> data = b.sceneData->read<glm::vec4>(o2.y);
  EXPECT_EQ(glm::vec3(data[o.x + vertex * 2u]), quad.positions[2]);  // vertex 2's position
  EXPECT_EQ(data[o.x + vertex * 2u + 4u], quad.colors[2]);           // and its color
  for (unsigned m = 0; m < materials; ++m)
    EXPECT_EQ(glm::vec3(data[o.y + shared::kMaterialRecordVec4s * m]), scene.materials[m].baseColor)
        << m;
  for (unsigned s = 0; s < spheres; ++s)
    EXPECT_EQ(data[o2.x + 2u * s], glm::vec4(scene.spheres[s].center, scene.spheres[s].radius))
        << s;
  const std::vector<std::uint32_t> words = b.words->read<std::uint32_t>(6);
  EXPECT_EQ(words, quad.indices);
  EXPECT_TRUE(b.iesTables.empty());
}
