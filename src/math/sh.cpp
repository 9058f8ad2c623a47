#include "ibl/math/sh.hpp"
#include "ibl/core/parallel.hpp"

#include <cmath>
#include <numbers>
#include <vector>

namespace ibl {

std::array<float, 9> shBasis9(glm::vec3 d) {
  std::array<float, 9> basis;
  for (int k = 0; k < 9; ++k) basis[k] = shBasis(k, d);
  return basis;
}

Sh9 projectSh9(const CubeMap& cube, int level) {
  const int n = cube.levels[level][0].width;
  const std::vector<double> omega = faceTexelSolidAngles(n);
  // One partial sum per face row, added in a fixed order: the same bits for any thread count.
  std::vector<std::array<glm::dvec3, 9>> rows(static_cast<std::size_t>(kFaceCount) * n);
  parallelFor(0, kFaceCount * n, [&](int row) {
    const int face = row / n, y = row % n;
    auto& acc = rows[row];
    acc.fill(glm::dvec3(0.0));
    for (int x = 0; x < n; ++x) {
      const auto basis = shBasis9(texelDirection(face, x, y, n));
      const glm::dvec3 l = glm::dvec3(cube.levels[level][face].at(x, y)) *
                           omega[static_cast<std::size_t>(y) * n + x];
      for (int k = 0; k < 9; ++k) acc[k] += l * static_cast<double>(basis[k]);
    }
  });
  std::array<glm::dvec3, 9> total{};
  for (const auto& r : rows)
    for (int k = 0; k < 9; ++k) total[k] += r[k];
  Sh9 sh;
  for (int k = 0; k < 9; ++k) sh[k] = glm::vec3(total[k]);
  return sh;
}

glm::vec3 evaluateSh9(const Sh9& sh, glm::vec3 d) {
  const auto basis = shBasis9(d);
  glm::vec3 sum(0.0f);
  for (int k = 0; k < 9; ++k) sum += sh[k] * basis[k];
  return sum;
}

glm::vec3 irradianceSh9(const Sh9& sh, glm::vec3 n) {
  const auto basis = shBasis9(n);
  glm::vec3 sum(0.0f);
  for (int k = 0; k < 9; ++k) sum += sh[k] * (basis[k] * shCosineLobe(shBand(k)));
  return sum;
}

Sh9 windowSh9(const Sh9& sh) {
  // sinc(pi l / (lmax + 1)) with lmax = 2.
  const auto sigma = [](int l) {
    if (l == 0) return 1.0f;
    const float x = std::numbers::pi_v<float> * static_cast<float>(l) / 3.0f;
    return std::sin(x) / x;
  };
  Sh9 out = sh;
  for (int k = 1; k < 9; ++k) out[k] *= sigma(k < 4 ? 1 : 2);
  return out;
}

}  // namespace ibl
