#pragma once
// Quadrature the light tests share, written apart from the code under test: the midpoint rule
// over parametric surfaces, in double precision.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

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

// The midpoint rule over the hemisphere of unit directions above the surface (+z; upper = false:
// below it), in (cos theta, phi), where d omega = d cos d phi: cells x cells points. f(l) takes a
// glm::vec3 and returns a number.
template <typename F>
double integrateOverHemisphere(const F& f, int cells, bool upper = true) {
  double sum = 0.0;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      const double c = (upper ? 1.0 : -1.0) * (i + 0.5) / cells;
      const double phi = 2.0 * std::numbers::pi * (j + 0.5) / cells;
      const double s = std::sqrt(1.0 - c * c);
      sum += f(glm::vec3(static_cast<float>(s * std::cos(phi)),
                         static_cast<float>(s * std::sin(phi)), static_cast<float>(c)));
    }
  return sum * 2.0 * std::numbers::pi / (double(cells) * cells);
}

// The unit direction at thetaDegrees from +z, phiDegrees around it from +x.
inline glm::dvec3 direction(double thetaDegrees, double phiDegrees = 0.0) {
  const double t = thetaDegrees * std::numbers::pi / 180.0,
               p = phiDegrees * std::numbers::pi / 180.0;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// The LTC table entry of the clamped cosine itself (Lambert): the identity transform.
inline const glm::vec4 kCosine(1.0f, 0.0f, 0.0f, 1.0f);

// A rect centered at c (relative to the shaded point), emitting along m, of w x h.
struct Rect {
  glm::dvec3 c, m, up;
  double w, h;
  [[nodiscard]] glm::dvec3 left() const { return glm::cross(up, m); }
  [[nodiscard]] glm::dvec3 at(double u, double v) const {
    return c + (u - 0.5) * w * left() + (v - 0.5) * h * up;
  }
  [[nodiscard]] glm::vec3 corner(int i) const {
    return glm::vec3(at(i < 2 ? 0.0 : 1.0, i == 0 || i == 3 ? 1.0 : 0.0));
  }
  template <typename F>
  [[nodiscard]] double integrate(const F& f, int steps = 500) const {
    return integrateOverPatch(
        f, [&](double u, double v) { return at(u, v); }, [&](double, double) { return m; },
        [&](double, double) { return w * h; }, steps);
  }
};

// A rect facing the point from direction `dir` at distance d, turned by `tilt` radians.
inline Rect rectToward(glm::dvec3 dir, double d, double tilt, double w, double h) {
  glm::dvec3 t, b;
  completeFrame(dir, t, b);
  const glm::dvec3 m = glm::normalize(-std::cos(tilt) * dir + std::sin(tilt) * t);
  return Rect{d * dir, m, glm::normalize(glm::cross(m, t)), w, h};
}

// The sheen lobe of KHR_materials_sheen written from its papers, apart from ibl/shared/brdf.h.
// The Charlie distribution (Estevez & Kulla 2017, eq. 2), alpha = r^2.
inline double charlieDistributionFromPaper(double NoH, double alpha) {
  const double pi = 3.14159265358979323846;
  return (2.0 + 1.0 / alpha) * std::pow(std::max(0.0, 1.0 - NoH * NoH), 0.5 / alpha) / (2.0 * pi);
}
// Their fit of the Smith Lambda (section 3, as KHR_materials_sheen's implementation notes give
// it): ln Lambda(mu) = L(mu) = a / (1 + b mu^c) + d mu + e below mu = 0.5 and 2 L(0.5) -
// L(1 - mu) above, the coefficients at r = 0 and r = 1 mixed by t = (1 - alpha)^2.
inline double charlieLambdaFromPaper(double mu, double alpha) {
  const double t = (1.0 - alpha) * (1.0 - alpha);
  const auto fit = [&](double x) {
    const auto at = [&](double r1, double r0) { return r1 + (r0 - r1) * t; };
    return at(21.5473, 25.3245) / (1.0 + at(3.82987, 3.32435) * std::pow(x, at(0.19823, 0.16801))) +
           at(-1.97760, -1.27393) * x + at(-4.32054, -4.85967);
  };
  return mu < 0.5 ? std::exp(fit(mu)) : std::exp(2.0 * fit(0.5) - fit(1.0 - mu));
}
// The integral over half vectors h of the upper hemisphere of f(h, c_h) dh by the midpoint rule
// in (u, phi) with cos theta_h = u^2: the points crowd toward the horizon, where the Charlie
// distribution lives (at r = 0.1 it falls by e from c_h = 0 to 0.14). phi over [0, pi], doubled:
// f must be even in h.y.
template <typename F>
double halfVectorQuadrature(const F& f, int steps) {
  const double pi = 3.14159265358979323846;
  double sum = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double u = (i + 0.5) / steps, c = u * u, s = std::sqrt(1.0 - c * c);
    for (int j = 0; j < steps; ++j) {
      const double phi = (j + 0.5) / steps * pi;
      sum += f(glm::dvec3(s * std::cos(phi), s * std::sin(phi), c)) * 2.0 * u;
    }
  }
  return sum * 2.0 * pi / (static_cast<double>(steps) * steps);
}

// The Smith Lambda of the Charlie distribution itself (Smith masking, Heitz 2014: G1(v) =
// n.v / integral of max(0, v.h) D(h) dh = 1 / (1 + Lambda)), at n.v = mu: the quantity
// that Estevez & Kulla's Lambda fits.
inline double charlieSmithLambda(double mu, double alpha, int steps = 600) {
  const glm::dvec3 v(std::sqrt(1.0 - mu * mu), 0.0, mu);
  return halfVectorQuadrature(
             [&](glm::dvec3 h) {
               return std::max(0.0, glm::dot(v, h)) * charlieDistributionFromPaper(h.z, alpha);
             },
             steps) /
             mu -
         1.0;
}

// Lambda as the renderers take it (ibl/shared/brdf.h): the paper's fit, or the Smith Lambda of D
// where the fit falls short of it. The Smith Lambda at one alpha from charlieSmithLambda's
// quadrature at `angles` angles uniform in theta, its projected area mu (1 + Lambda) (smooth in
// theta) interpolated linearly between them: for integrands that need it at every point.
class CharlieLambdaFromPapers {
 public:
  explicit CharlieLambdaFromPapers(double alpha, int angles = 129, int steps = 200)
      : alpha_(alpha), area_(angles) {
    for (int i = 0; i < angles; ++i) {
      const double mu = std::max(std::cos(angleAt(i)), 1e-9);
      area_[i] = mu * (1.0 + charlieSmithLambda(mu, alpha, steps));
    }
  }
  [[nodiscard]] double smith(double mu) const {
    const double x = std::acos(std::clamp(mu, 0.0, 1.0)) / angleAt(1);
    const int i = std::min(static_cast<int>(x), static_cast<int>(area_.size()) - 2);
    const double t = x - i;
    return ((1.0 - t) * area_[i] + t * area_[i + 1]) / std::max(mu, 1e-9) - 1.0;
  }
  [[nodiscard]] double operator()(double mu) const {
    return std::max(charlieLambdaFromPaper(mu, alpha_), smith(mu));
  }

 private:
  [[nodiscard]] double angleAt(int i) const {
    return 0.5 * 3.14159265358979323846 * i / (static_cast<double>(area_.size()) - 1.0);
  }
  double alpha_;
  std::vector<double> area_;
};

// The sheen lobe's visibility: Charlie's with Lambda as the renderers take it (the default),
// with the paper's fit alone (whose albedo passes 1 at small roughness and grazing n.v), or
// Neubelt & Pettineo's 1 / (4 (n.l + n.v - n.l n.v)).
enum class SheenModel { Charlie, CharlieFitAlone, Neubelt };

// The sheen lobe's directional albedo E(n.v, r) = integral of D V (n.l) dl, over half vectors
// (l = 2 (v.h) h - v, dl = 4 (v.h) dh), V = G2 / (4 n.v n.l), G2 = 1 / (1 + Lambda(n.v) +
// Lambda(n.l)) for Charlie's. 600^2 points: within 1e-3 relative of 1500^2 from r = 0.1 up, at
// every n.v.
inline double sheenAlbedoQuadrature(double NoV, double roughness,
                                    SheenModel model = SheenModel::Charlie, int steps = 600) {
  const double alpha = roughness * roughness;
  const glm::dvec3 v(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
  std::optional<CharlieLambdaFromPapers> lambda;
  if (model == SheenModel::Charlie) lambda.emplace(alpha);
  const auto lambdaAt = [&](double mu) {
    return lambda ? (*lambda)(mu) : charlieLambdaFromPaper(mu, alpha);
  };
  const double lambdaV = lambdaAt(NoV);
  return halfVectorQuadrature(
      [&](glm::dvec3 h) {
        const double VoH = glm::dot(v, h), NoL = 2.0 * VoH * h.z - NoV;
        if (VoH <= 0.0 || NoL <= 0.0) return 0.0;
        const double visibility = model == SheenModel::Neubelt
                                      ? 1.0 / (4.0 * (NoL + NoV - NoL * NoV))
                                      : 1.0 / ((1.0 + lambdaV + lambdaAt(NoL)) * (4.0 * NoV * NoL));
        return charlieDistributionFromPaper(h.z, alpha) * visibility * NoL * 4.0 * VoH;
      },
      steps);
}

// The GGX lobe written from its papers, apart from ibl/shared/brdf.h: the distribution (Walter et
// al. 2007, eq. 33) and the height-correlated Smith masking-shadowing (Heitz 2014, eq. 99, with
// Lambda from eq. 72), alpha = r^2.
inline double ggxDistributionFromPaper(double NoH, double alpha) {
  const double pi = 3.14159265358979323846;
  const double c2 = NoH * NoH, t2 = (1.0 - c2) / c2, a2 = alpha * alpha;
  return a2 / (pi * c2 * c2 * (a2 + t2) * (a2 + t2));
}
inline double ggxLambdaFromPaper(double mu, double alpha) {
  const double t2 = (1.0 - mu * mu) / (mu * mu);
  return 0.5 * (-1.0 + std::sqrt(1.0 + alpha * alpha * t2));
}

// The specular lobe's directional albedo with Schlick's Fresnel between f0 and f90: the integral
// of D G2 F / (4 n.v n.l) (n.l) dl over half vectors (l = 2 (v.h) h - v, dl = 4 (v.h) dh), by
// the midpoint rule in (theta_h, phi) (steps^2 points; the lobe is near the normal).
inline double ggxAlbedoQuadrature(double NoV, double roughness, double f0, double f90,
                                  int steps = 800) {
  const double pi = 3.14159265358979323846, alpha = roughness * roughness;
  const glm::dvec3 v(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
  double sum = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double theta = (i + 0.5) / steps * 0.5 * pi;
    for (int j = 0; j < steps; ++j) {
      const double phi = (j + 0.5) / steps * 2.0 * pi;
      const glm::dvec3 h(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                         std::cos(theta));
      const double VoH = glm::dot(v, h), NoL = 2.0 * VoH * h.z - NoV;
      if (VoH <= 0.0 || NoL <= 0.0) continue;
      const double g2 =
          1.0 / (1.0 + ggxLambdaFromPaper(NoV, alpha) + ggxLambdaFromPaper(NoL, alpha));
      const double fresnel = f0 + (f90 - f0) * std::pow(1.0 - VoH, 5.0);
      sum += ggxDistributionFromPaper(h.z, alpha) * g2 * fresnel / (4.0 * NoV) * 4.0 * VoH *
             std::sin(theta);
    }
  }
  return sum * (0.5 * pi / steps) * (2.0 * pi / steps);
}

// Fresnel's equations for unpolarized light meeting a dielectric of relative index n from
// outside at incidence cos(theta) = c: the mean of the s and p reflectances.
inline double fresnelDielectric(double c, double n) {
  const double s2 = 1.0 - c * c, t2 = s2 / (n * n);
  if (t2 >= 1.0) return 1.0;
  const double ct = std::sqrt(1.0 - t2);
  const double rs = (c - n * ct) / (c + n * ct), rp = (n * c - ct) / (n * c + ct);
  return 0.5 * (rs * rs + rp * rp);
}

// The cosine-weighted mean over the hemisphere of light directions l of (1 - v.h)^5, h =
// normalize(v + l), at n.v = NoV: the midpoint rule over (sin^2 theta, phi), in which the cosine
// weight is uniform. glTF's fresnel_mix takes specular (F0 + (1 - F0) this) from a Lambertian
// diffuse under uniform light.
inline double lambertianSchlickMeanQuadrature(double NoV, int steps = 160) {
  const glm::dvec3 v(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
  double sum = 0.0;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < steps; ++j) {
      const double u = (i + 0.5) / steps, phi = 2.0 * 3.14159265358979 * (j + 0.5) / steps;
      const glm::dvec3 l(std::sqrt(u) * std::cos(phi), std::sqrt(u) * std::sin(phi),
                         std::sqrt(1.0 - u));
      sum += std::pow(1.0 - glm::dot(v, glm::normalize(v + l)), 5.0);
    }
  return sum / (steps * steps);
}

}  // namespace ibl::test
