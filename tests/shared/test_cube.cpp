// Cube-map geometry (ibl/shared/cube.h): texel directions against the face table of
// docs/conventions.md, and directions to faces and back.
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/env/cubemap.hpp"

using namespace ibl;

namespace {

// The face table of docs/conventions.md: major axis, and the directions in which s and t grow.
struct FaceAxes {
  glm::vec3 major, s, t;
};
constexpr FaceAxes kTable[6] = {
    {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}},   // +X: sc = -z, tc = -y
    {{-1, 0, 0}, {0, 0, 1}, {0, -1, 0}},   // -X: sc = +z, tc = -y
    {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},     // +Y: sc = +x, tc = +z
    {{0, -1, 0}, {1, 0, 0}, {0, 0, -1}},   // -Y: sc = +x, tc = -z
    {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}},    // +Z: sc = +x, tc = -y
    {{0, 0, -1}, {-1, 0, 0}, {0, -1, 0}},  // -Z: sc = -x, tc = -y
};

}  // namespace

TEST(CubeMap, TexelDirectionsFollowTheMajorAxisTable) {
  const int n = 8;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const float sc = 2.0f * (x + 0.5f) / n - 1.0f, tc = 2.0f * (y + 0.5f) / n - 1.0f;
        const glm::vec3 expected =
            glm::normalize(kTable[f].major + sc * kTable[f].s + tc * kTable[f].t);
        const glm::vec3 d = texelDirection(f, x, y, n);
        ASSERT_NEAR(glm::distance(d, expected), 0.0f, 1e-6f) << "face " << f;
      }
}

TEST(CubeMap, TexelDirectionRoundTrip) {
  for (int n : {1, 2, 7, 32}) {
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const FacePoint p = directionToFace(texelDirection(f, x, y, n));
          ASSERT_EQ(p.face, f);
          ASSERT_NEAR(p.s * n, x + 0.5f, 1e-4f);
          ASSERT_NEAR(p.t * n, y + 0.5f, 1e-4f);
        }
  }
}

TEST(CubeMap, RandomDirectionsRoundTrip) {
  std::mt19937 rng(5);
  std::normal_distribution<float> g;
  for (int i = 0; i < 10000; ++i) {
    const glm::vec3 d = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    const FacePoint p = directionToFace(d);
    const glm::vec3 back = glm::normalize(faceToDirection(p.face, 2 * p.s - 1, 2 * p.t - 1));
    ASSERT_NEAR(glm::distance(d, back), 0.0f, 1e-5f);
  }
}
