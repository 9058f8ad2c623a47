#pragma once
// What the material extensions' loader tests share: the surface writeMaterialQuad's quad shows,
// and the refusal of an extension's forbidden values.
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../../src/render/ray_tracer.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/render/renderer.hpp"
#include "support/helpers.hpp"

namespace ibl::test {

// The surface point of writeMaterialQuad's quad at (0.1, 0.2), seen from +Z.
inline SurfacePoint quadSurface(const Scene& scene) {
  const RayTracer tracer(scene);
  const Ray ray{glm::vec3(0.1f, 0.2f, 3.0f), glm::vec3(0.0f, 0.0f, -1.0f)};
  const RayTracer::Hit hit = tracer.intersect(ray);
  EXPECT_TRUE(hit.found);
  return surfaceAt(scene, tracer, hit, ray);
}

// Each bad object (JSON) in place of the first material's `extension` in the glTF file `good`:
// loading it fails with one line naming the file (bad.gltf, beside `good`) and `message`.
inline void expectExtensionRefused(
    const std::filesystem::path& good, const std::string& extension,
    const std::vector<std::pair<std::string, std::string>>& badObjects) {
  const std::filesystem::path bad = good.parent_path() / "bad.gltf";
  for (const auto& [object, message] : badObjects) {
    nlohmann::json gltf = nlohmann::json::parse(std::ifstream(good));
    gltf["materials"][0]["extensions"][extension] = nlohmann::json::parse(object);
    std::ofstream(bad) << gltf.dump();
    const std::string error = errorOf([&] { loadGltf(bad.string()); });
    EXPECT_NE(error.find("bad.gltf"), std::string::npos) << error;
    EXPECT_NE(error.find(message), std::string::npos) << error;
  }
}

}  // namespace ibl::test
