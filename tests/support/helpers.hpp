#pragma once
// Helpers shared by the tests: temporary directories, synthetic environments, comparisons.
#include <cmath>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>

#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/core/image.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/equirect.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/scene.hpp"
#include "support/run_command.hpp"

namespace ibl::test {

inline std::filesystem::path dataDir() {
  return IBL_TEST_DATA;
}
inline std::filesystem::path hdriPath(const std::string& name) {
  return dataDir() / "hdri" / (name + ".exr");
}
// The repository's root: the folder above data/ (and tests/).
inline std::filesystem::path repositoryRoot() {
  return dataDir().parent_path();
}

// A fresh, empty directory under the system temp directory, removed by the destructor.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("ibl_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

using RadianceFn = std::function<glm::vec3(glm::vec3)>;

// Equirect map whose pixels hold f at their center direction.
inline Image equirectFromFunction(int width, const RadianceFn& f) {
  Image img(width, width / 2);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      img.at(x, y) = f(equirectToDirection((x + 0.5f) / img.width, (y + 0.5f) / img.height));
  return img;
}

// Cube map whose texels hold f at their center direction.
inline CubeMap cubeFromFunction(int size, const RadianceFn& f) {
  CubeMap cube(size, 1);
  for (int face = 0; face < kFaceCount; ++face)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        cube.levels[0][face].at(x, y) = f(texelDirection(face, x, y, size));
  return cube;
}

inline Environment equirectEnvironment(Image img) {
  Environment env;
  env.layout = Layout::Equirect;
  env.equirect = std::move(img);
  return env;
}

inline Environment cubeEnvironment(CubeMap cube) {
  Environment env;
  env.layout = Layout::Cube;
  env.cube = std::move(cube);
  return env;
}

inline Image randomImage(int w, int h, unsigned seed, float maxValue = 100.0f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Image img(w, h);
  for (auto& p : img.pixels) {
    // Log-uniform over a wide range, as HDR data is.
    p = glm::vec3(u(rng), u(rng), u(rng));
    p = glm::exp2(p * 20.0f - 12.0f) * (maxValue / 256.0f);
  }
  return img;
}

// stb_image_write callback that appends the written bytes to a std::vector<std::uint8_t>.
inline void appendToVector(void* vector, void* data, int size) {
  auto* v = static_cast<std::vector<std::uint8_t>*>(vector);
  v->insert(v->end(), static_cast<std::uint8_t*>(data), static_cast<std::uint8_t*>(data) + size);
}

// An orthographic camera on +Z looking at the origin: `width` wide, pixels x pixels.
inline Camera frontOrthoCamera(float width, int pixels, float distance = 4.0f) {
  Camera c;
  c.perspective = false;
  c.orthoWidth = width;
  c.from = glm::vec3(0.0f, 0.0f, distance);
  c.width = c.height = pixels;
  return c;
}

inline double maxRelativeError(glm::vec3 a, glm::vec3 ref) {
  double e = 0.0;
  for (int c = 0; c < 3; ++c)
    e = std::max(e, std::abs(double(a[c]) - ref[c]) / std::max(1e-30, std::abs(double(ref[c]))));
  return e;
}

// Runs the `ibl` executable with `args`.
inline CliRun runIbl(const std::string& args) {
  return runCommand(std::string(IBL_CLI) + " " + args);
}

inline std::string quote(const std::filesystem::path& p) {
  return "'" + p.string() + "'";
}

// The message of the ibl::Error that `f` throws, or "" when it throws none.
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A smooth glass of color c that transmits everything below its specular layer
// (KHR_materials_transmission 1, ior 1.5: F0 = 0.04), thin-walled unless given a thickness.
inline Material smoothGlass(glm::vec3 c) {
  Material m;
  m.baseColor = c;
  m.metallic = 0.0f;
  m.roughness = 0.0f;
  m.transmission = 1.0f;
  return m;
}

}  // namespace ibl::test
