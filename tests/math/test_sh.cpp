#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/math/sh.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {
constexpr float kPi = std::numbers::pi_v<float>;
}

TEST(Sh, BasisIsOrthonormal) {
  // Exact texel solid angles make the discrete inner products match the continuous ones.
  const int n = 64;
  double gram[9][9] = {};
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const auto b = shBasis9(texelDirection(f, x, y, n));
        const double w = texelSolidAngle(x, y, n);
        for (int i = 0; i < 9; ++i)
          for (int j = 0; j < 9; ++j) gram[i][j] += b[i] * b[j] * w;
      }
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) EXPECT_NEAR(gram[i][j], i == j ? 1.0 : 0.0, 2e-3) << i << "," << j;
}

TEST(Sh, ProjectionRecoversKnownCoefficients) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Sh9 truth;
  for (auto& c : truth) c = glm::vec3(u(rng), u(rng), u(rng));
  const CubeMap cube = cubeFromFunction(64, [&](glm::vec3 d) { return evaluateSh9(truth, d); });
  const Sh9 sh = projectSh9(cube);
  for (int k = 0; k < 9; ++k)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sh[k][c], truth[k][c], 3e-3) << k;
  // And back: reconstruction reproduces the function.
  const glm::vec3 d = glm::normalize(glm::vec3(0.2f, -0.7f, 0.4f));
  EXPECT_LT(glm::distance(evaluateSh9(sh, d), evaluateSh9(truth, d)), 1e-2f);
}

TEST(Sh, ConstantEnvironmentGivesPiL) {
  const CubeMap cube = cubeFromFunction(32, [](glm::vec3) { return glm::vec3(2.0f, 1.0f, 0.5f); });
  const Sh9 sh = projectSh9(cube);
  for (glm::vec3 n : {glm::vec3(0, 1, 0), glm::normalize(glm::vec3(1, -2, 3))}) {
    const glm::vec3 e = irradianceSh9(sh, n);
    EXPECT_NEAR(e.x, kPi * 2.0f, 1e-4f);
    EXPECT_NEAR(e.z, kPi * 0.5f, 1e-5f);
  }
}

TEST(Sh, IrradianceOfALinearEnvironmentIsExact) {
  // L(w) = 1 + a.w has E(n) = pi + (2 pi / 3) a.n exactly: bands 0 and 1 only.
  const glm::vec3 a(0.3f, -0.5f, 0.2f);
  const CubeMap cube =
      cubeFromFunction(64, [&](glm::vec3 d) { return glm::vec3(1.0f + glm::dot(a, d)); });
  const Sh9 sh = projectSh9(cube);
  for (glm::vec3 n : {glm::vec3(0, 0, 1), glm::normalize(glm::vec3(1, 1, -1))})
    EXPECT_NEAR(irradianceSh9(sh, n).x, kPi + 2.0f * kPi / 3.0f * glm::dot(a, n), 2e-3f);
}

TEST(Sh, SkyIrradianceClosedForm) {
  // Upper hemisphere of radiance 1: E(n) = pi (1 + n.y) / 2. Its Legendre coefficients are
  // 1/2, 3/4, 0 (every even one above 0 vanishes) and the cosine lobe's vanish for odd l > 1,
  // so SH9 gives it exactly; what remains is the step's sampling on the 64^2 cube.
  const CubeMap cube =
      cubeFromFunction(64, [](glm::vec3 d) { return glm::vec3(d.y > 0 ? 1.0f : 0.0f); });
  const Sh9 sh = projectSh9(cube);
  for (float ny : {-0.9f, -0.3f, 0.0f, 0.5f, 1.0f}) {
    const glm::vec3 n(std::sqrt(1 - ny * ny), ny, 0);
    EXPECT_NEAR(irradianceSh9(sh, n).x, kPi * (1 + ny) / 2, 4e-3f) << ny;
  }
}

// Pure band-2 content: E = A_2 L = (pi / 4) L for L = xy, 3z^2 - 1 and x^2 - y^2 (R&H eq. 8),
// beside a constant (E = pi).
TEST(Sh, Band2Irradiance) {
  const std::function<float(glm::vec3)> band2[] = {
      [](glm::vec3 d) { return d.x * d.y; }, [](glm::vec3 d) { return 3 * d.z * d.z - 1; },
      [](glm::vec3 d) { return d.x * d.x - d.y * d.y; }, [](glm::vec3 d) { return d.y * d.z; }};
  for (const auto& f : band2) {
    const CubeMap cube = cubeFromFunction(64, [&](glm::vec3 d) { return glm::vec3(2.0f + f(d)); });
    const Sh9 sh = projectSh9(cube);
    for (glm::vec3 n : {glm::vec3(0, 0, 1), glm::normalize(glm::vec3(1, 1, -1)),
                        glm::normalize(glm::vec3(-0.3f, 0.8f, 0.5f))})
      EXPECT_NEAR(irradianceSh9(sh, n).x, 2.0f * kPi + kPi / 4.0f * f(n), 2e-3f);
  }
}

TEST(Sh, WindowScalesBands) {
  Sh9 sh;
  sh.fill(glm::vec3(1.0f));
  const Sh9 w = windowSh9(sh);
  EXPECT_FLOAT_EQ(w[0].x, 1.0f);
  EXPECT_NEAR(w[2].x, 0.826993f, 1e-5f);  // sin(pi/3) / (pi/3)
  EXPECT_NEAR(w[7].x, 0.413497f, 1e-5f);  // sin(2pi/3) / (2pi/3)
}
