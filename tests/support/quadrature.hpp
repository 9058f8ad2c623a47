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

// The sheen lobe's directional albedo E(n.v, r) = integral of D_charlie V_neubelt (n.l) dl by
// the midpoint rule over (cos theta_l, phi), with the distribution and visibility written from
// their papers (Estevez & Kulla 2017, eq. 2; Neubelt & Pettineo 2013).
inline double sheenAlbedoQuadrature(double NoV, double roughness, int steps = 600) {
  const double pi = 3.14159265358979323846, alpha = roughness * roughness;
  const glm::dvec3 v(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
  double sum = 0.0;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < 2 * steps; ++j) {
      const double c = (i + 0.5) / steps, phi = (j + 0.5) / (2 * steps) * 2.0 * pi;
      const double s = std::sqrt(1.0 - c * c);
      const glm::dvec3 l(s * std::cos(phi), s * std::sin(phi), c);
      const glm::dvec3 h = glm::normalize(v + l);
      const double d =
          (2.0 + 1.0 / alpha) * std::pow(std::max(0.0, 1.0 - h.z * h.z), 0.5 / alpha) / (2.0 * pi);
      sum += d / (4.0 * (c + NoV - c * NoV)) * c;
    }
  return sum * 2.0 * pi / (static_cast<double>(steps) * 2 * steps);
}

}  // namespace ibl::test
