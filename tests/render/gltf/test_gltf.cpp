// The glTF loader through its public API (include/ibl/render/gltf.hpp): a file loads, with
// its node transforms applied and what it lacks generated; what it cannot read is one line
// naming the file.
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/render/gltf.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/hostile_gltf.hpp"

using namespace ibl;
using namespace ibl::test;

TEST(Gltf, LoadsATexturedQuad) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf");
  const Scene s = loadGltf((dir / "quad.gltf").string());
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.indices.size(), 6u);
  EXPECT_NEAR(m.positions[2].z, 0.5f, 1e-6f);                         // node translation applied
  EXPECT_LT(glm::distance(m.normals[0], glm::vec3(0, 0, 1)), 1e-5f);  // generated
  ASSERT_EQ(m.tangents.size(), 4u);  // generated for the normal map
  EXPECT_LT(glm::distance(glm::vec3(m.tangents[0]), glm::vec3(1, 0, 0)), 1e-5f);
  const Material& mat = s.materials[m.material];
  EXPECT_FLOAT_EQ(mat.roughness, 0.8f);
  ASSERT_GE(mat.baseColorTexture.index, 0);
  const Texture& base = s.textures[mat.baseColorTexture.index];
  EXPECT_NEAR(base.sample({0.375f, 0.5f}, true).x, 1.0f, 1e-6f);
  EXPECT_NEAR(base.sample({0.625f, 0.5f}, true).z, 1.0f, 1e-6f);
}

TEST(Gltf, BadFilesAreRejectedClearly) {
  TempDir dir;
  std::ofstream(dir / "text.gltf") << "this is not json";
  std::ofstream(dir / "empty.gltf") << R"({"asset": {"version": "2.0"}})";
  std::ofstream(dir / "missing.gltf")
      << R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":12,"uri":"nope.bin"}]})";
  for (const char* name : {"text.gltf", "empty.gltf", "missing.gltf", "absent.glb"}) {
    const std::string path = (dir / name).string();
    try {
      loadGltf(path);
      FAIL() << name;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

TEST(GltfHostile, TheBaseFileLoads) {
  TempDir dir;
  const std::string path = write(dir, "base.gltf", baseGltf());
  const Scene s = loadGltf(path);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].indices.size(), 3u);
  EXPECT_EQ(s.lights.size(), 1u);
  EXPECT_TRUE(s.camera.has_value());
  EXPECT_GE(s.materials[0].baseColorTexture.index, 0);
  const std::vector<std::uint8_t> glb = asGlb(baseGltf());
  writeFileAtomic(dir / "base.glb", glb);
  EXPECT_EQ(loadGltf((dir / "base.glb").string()).meshes.size(), 1u);
}
