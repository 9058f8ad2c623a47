#pragma once
// Quadrature the light tests share, written apart from the code under test: the midpoint rule
// over parametric surfaces, in double precision.
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace ibl::test {

// Two unit vectors completing unit `a` to an orthonormal frame.
inline void completeFrame(glm::dvec3 a, glm::dvec3& t, glm::dvec3& b) {
  t = glm::normalize(
      glm::cross(std::abs(a.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), a));
  b = glm::cross(a, t);
}

// The midpoint rule over a parametric patch seen from the origin: the integral of
// f(w) (m.-w) / d^2 dA over the parts facing the origin, for position q(u, v), unit normal
// m(u, v), (u, v) in [0, 1]^2 and area element jacobian(u, v); w the unit direction to the point.
// With f(w) = max(0, n.w): the illuminance from a surface of luminance 1 on a normal n.
template <typename F, typename Q, typename M, typename J>
double integrateOverPatch(const F& f, const Q& q, const M& m, const J& jacobian, int steps = 400) {
  double sum = 0.0;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < steps; ++j) {
      const double u = (i + 0.5) / steps, v = (j + 0.5) / steps;
      const glm::dvec3 p = q(u, v);
      const double d2 = glm::dot(p, p);
      const glm::dvec3 w = p / std::sqrt(d2);
      const double facing = -glm::dot(m(u, v), w);
      if (facing > 0.0) sum += f(w) * facing / d2 * jacobian(u, v);
    }
  return sum / (static_cast<double>(steps) * steps);
}

}  // namespace ibl::test
