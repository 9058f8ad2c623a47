// ibl_ltc_lights: the area lights through LTCs (ibl/shared/lights.h, ltc.h) against quadrature
// over the light, per pixel, over the whole lit region (the table in docs/lights.md, "The LTC
// table and its fit"). A unit sphere seen along +z (orthographic, v = +z at every pixel) is lit
// by one light of each area type 2.9 m from its center (toward (1, 1, 1)), facing it: a sphere
// of radius 0.5, a disk of radius 0.5, a tube 1.5 m x r 0.1 (axis across the light's
// direction), a rect 1.2 x 0.6 m; 10 nits each. Materials: Lambert (base color 1, the diffuse
// alone) and a metal (base color 0.9, Schlick's Fresnel, f90 = 1, no multiple scattering) at
// roughness 0.1 to 1. The reference is the BRDF times the cosine integrated over the light's
// surface by the midpoint rule (every convex light's point that faces the shaded point is
// visible from it), tens of thousands of points; the real-time value is lightIncidence and
// lightRadiance, as the CPU renderer calls them. Error per pixel: |real time - reference| /
// reference over every pixel whose reference is at least 1/1000 of the brightest (the lobe's
// tails included); mean and median over those pixels. The metal's specular twice: with the DFG
// table's F0 A + B (the shading's) and with the LTC table's second table, F0 (norm - fresnel) +
// fresnel (Heitz et al. 2016's).
//   ibl_ltc_lights [pixels across, default 64]
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <glm/geometric.hpp>

#include "ibl/bake/dfg.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/render/ltc.hpp"
#include "ibl/shared/lights.h"

using namespace ibl;
namespace s = ibl::shared;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr float kLuminance = 10.0f;

// A point of the light's surface for the midpoint rule: position, outward normal, area.
struct SurfacePoint {
  glm::dvec3 x, m;
  double area;
};

glm::dvec3 any(glm::dvec3 m) {
  return glm::normalize(
      glm::cross(m, std::abs(m.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
}

// Latitude-longitude points of the sphere (center c, radius r) with z0 in [zLo, zHi] along axis a
// (equal steps of z: equal areas).
void addSphereZone(std::vector<SurfacePoint>& out, glm::dvec3 c, double r, glm::dvec3 a, double zLo,
                   double zHi, int nz, int nphi) {
  const glm::dvec3 t = any(a), b = glm::cross(a, t);
  for (int i = 0; i < nz; ++i) {
    const double z = zLo + (zHi - zLo) * (i + 0.5) / nz, sn = std::sqrt(std::max(0.0, 1.0 - z * z));
    for (int j = 0; j < nphi; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / nphi;
      const glm::dvec3 m = z * a + sn * (std::cos(phi) * t + std::sin(phi) * b);
      out.push_back({c + r * m, m, 2.0 * kPi * r * r * (zHi - zLo) / (nz * nphi)});
    }
  }
}

std::vector<SurfacePoint> surfaceOf(const s::ShadingLight& l) {
  std::vector<SurfacePoint> out;
  const glm::dvec3 c(l.position), d(l.direction);
  if (l.type == s::kLightSphere) {
    addSphereZone(out, c, l.radius, glm::dvec3(0, 0, 1), -1.0, 1.0, 256, 256);
  } else if (l.type == s::kLightDisk) {
    const glm::dvec3 t = any(d), b = glm::cross(d, t);
    const int nr = 128, nphi = 256;
    for (int i = 0; i < nr; ++i) {
      const double rho = l.radius * std::sqrt((i + 0.5) / nr);  // equal areas
      for (int j = 0; j < nphi; ++j) {
        const double phi = 2.0 * kPi * (j + 0.5) / nphi;
        out.push_back({c + rho * (std::cos(phi) * t + std::sin(phi) * b), d,
                       kPi * l.radius * l.radius / (nr * nphi)});
      }
    }
  } else if (l.type == s::kLightRect) {
    const glm::dvec3 up(l.up), left = glm::cross(up, d);
    const int nu = 240, nv = 120;
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j)
        out.push_back(
            {c + ((i + 0.5) / nu - 0.5) * l.width * left + ((j + 0.5) / nv - 0.5) * l.height * up,
             d, static_cast<double>(l.width) * l.height / (nu * nv)});
  } else {  // tube: the cylinder and its two hemispherical caps
    const glm::dvec3 t = any(d), b = glm::cross(d, t);
    const double hl = 0.5 * l.width;
    const int na = 384, nphi = 128;
    for (int i = 0; i < na; ++i)
      for (int j = 0; j < nphi; ++j) {
        const double s = -hl + l.width * (i + 0.5) / na, phi = 2.0 * kPi * (j + 0.5) / nphi;
        const glm::dvec3 m = std::cos(phi) * t + std::sin(phi) * b;
        out.push_back({c + s * d + static_cast<double>(l.radius) * m, m,
                       2.0 * kPi * l.radius * l.width / (na * nphi)});
      }
    addSphereZone(out, c + hl * d, l.radius, d, 0.0, 1.0, 64, 128);
    addSphereZone(out, c - hl * d, l.radius, -d, 0.0, 1.0, 64, 128);
  }
  return out;
}

// The reflected radiance at p (normal n, view v) by quadrature over the light's surface.
double reference(const std::vector<SurfacePoint>& surface, const s::ShadingLight& l, glm::dvec3 p,
                 glm::dvec3 n, glm::dvec3 v, bool metal, double alpha) {
  const bool oneSided = l.type == s::kLightDisk || l.type == s::kLightRect;
  double sum = 0.0;
  const double a2 = alpha * alpha, NoV = glm::dot(n, v);
  for (const SurfacePoint& q : surface) {
    const glm::dvec3 w = q.x - p;
    const double d2 = glm::dot(w, w);
    const glm::dvec3 l3 = w / std::sqrt(d2);
    const double cosLight = -glm::dot(q.m, l3);
    const double NoL = glm::dot(n, l3);
    if (cosLight <= 0.0 || NoL <= 0.0) continue;
    (void)oneSided;  // both: a point faces p when its normal does (convex lights)
    double f;
    if (!metal) {
      f = 1.0 / kPi;
    } else {
      const glm::dvec3 h = glm::normalize(v + l3);
      const double NoH = glm::dot(n, h), VoH = std::max(0.0, glm::dot(v, h));
      const double dd = NoH * NoH * (a2 - 1.0) + 1.0, D = a2 / (kPi * dd * dd);
      const double lv = NoL * std::sqrt(NoV * NoV * (1.0 - a2) + a2);
      const double ll = NoV * std::sqrt(NoL * NoL * (1.0 - a2) + a2);
      const double vis = 0.5 / (lv + ll);
      const double F = 0.9 + 0.1 * std::pow(1.0 - VoH, 5.0);
      f = D * vis * F;
    }
    sum += f * NoL * cosLight / d2 * q.area;
  }
  return sum * kLuminance;
}

s::ShadingLight studyLight(int type) {
  s::ShadingLight l{};
  const glm::vec3 toward = glm::normalize(glm::vec3(1.0f, 1.0f, 1.0f));
  l.type = type;
  l.position = 2.9f * toward;
  l.direction = -toward;
  l.color = glm::vec3(kLuminance);
  l.invSquaredRange = 0.0f;
  if (type == s::kLightSphere) l.radius = 0.5f;
  if (type == s::kLightDisk) l.radius = 0.5f;
  if (type == s::kLightTube) {
    l.direction = glm::normalize(glm::cross(toward, glm::vec3(0.0f, 1.0f, 0.0f)));
    l.radius = 0.1f;
    l.width = 1.5f;
  }
  if (type == s::kLightRect) {
    l.up = glm::normalize(glm::cross(l.direction, glm::vec3(1.0f, 0.0f, 0.0f)));
    l.width = 1.2f;
    l.height = 0.6f;
  }
  return l;
}

struct Error {
  double mean = 0.0, median = 0.0;
  int pixels = 0;
};

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 64;
  const Image dfgLut = integrateDfgLut(128, 128, 512);  // as the default bake
  const float roughnesses[] = {0.1f, 0.25f, 0.5f, 0.75f, 1.0f};
  const char* names[] = {"sphere", "disk", "tube", "rect"};
  const int types[] = {s::kLightSphere, s::kLightDisk, s::kLightTube, s::kLightRect};
  const auto measure = [&](int type, bool metal, float roughness) {
    const s::ShadingLight light = studyLight(type);
    const std::vector<SurfacePoint> surface = surfaceOf(light);
    std::vector<double> ref(static_cast<std::size_t>(n) * n, -1.0), fast(ref.size(), 0.0),
        fastNorm(ref.size(), 0.0);
    const double alpha = std::max(roughness * roughness, 1e-3f);
    parallelFor(0, n, [&](int y) {
      for (int x = 0; x < n; ++x) {
        const double px = 2.0 * (x + 0.5) / n - 1.0, py = 1.0 - 2.0 * (y + 0.5) / n;
        const double r2 = px * px + py * py;
        if (r2 >= 1.0) continue;
        const glm::dvec3 nd(px, py, std::sqrt(1.0 - r2)), v(0, 0, 1);
        const std::size_t i = static_cast<std::size_t>(y) * n + x;
        ref[i] = reference(surface, light, nd, nd, v, metal, alpha);
        s::SplitSumSwitches sw{};
        sw.terms = metal ? 2 : 1;
        sw.ltcAreaLights = true;
        s::SplitSumMaterial m{};
        m.baseColor = glm::vec3(metal ? 0.9f : 1.0f);
        m.metallic = metal ? 1.0f : 0.0f;
        m.roughness = roughness;
        m.occlusion = 1.0f;
        const glm::vec3 nf(nd), vf(v);
        const float NoV = std::max(nf.z, 1e-4f);
        const glm::vec4 ltc = ltcTableLookup(roughness, NoV);
        const s::LightIncidence inc = s::lightIncidence(light, nf, nf, vf, roughness, sw, ltc);
        const glm::vec3 dfg = sampleDfgLut(dfgLut, NoV, roughness);
        fast[i] = kLuminance * s::lightRadiance(m, nf, vf, inc, glm::vec2(dfg), sw).x;
        const glm::vec4 norm = ltcNormLookup(roughness, NoV);
        fastNorm[i] = metal ? kLuminance * (0.9 * (norm.x - norm.y) + norm.y) *
                                  std::max(0.0f, inc.specularLobeFraction)
                            : fast[i];
      }
    });
    double peak = 0.0;
    for (double r : ref) peak = std::max(peak, r);
    const auto errorOf = [&](const std::vector<double>& approx) {
      std::vector<double> rel;
      for (std::size_t i = 0; i < ref.size(); ++i)
        if (ref[i] >= 1e-3 * peak && ref[i] > 0.0)
          rel.push_back(std::abs(approx[i] - ref[i]) / ref[i]);
      Error e;
      e.pixels = static_cast<int>(rel.size());
      for (double r : rel) e.mean += r / static_cast<double>(rel.size());
      std::nth_element(rel.begin(), rel.begin() + static_cast<std::ptrdiff_t>(rel.size() / 2),
                       rel.end());
      e.median = rel.empty() ? 0.0 : rel[rel.size() / 2];
      return e;
    };
    return std::array<Error, 2>{errorOf(fast), errorOf(fastNorm)};
  };
  fmt::print(
      "unit sphere, {}^2 pixels, lights at 2.9 m; per-pixel |LTC - quadrature| / quadrature "
      "over every pixel >= 1/1000 of the peak: mean / median %\n",
      n);
  fmt::print("| light | Lambert | metal r = 0.1 | r = 0.25 | r = 0.5 | r = 0.75 | r = 1 |\n");
  fmt::print("| --- | --- | --- | --- | --- | --- | --- |\n");
  std::vector<std::string> normRows;
  for (int k = 0; k < 4; ++k) {
    std::string row = fmt::format("| {} |", names[k]), normRow = row;
    const Error lambert = measure(types[k], false, 0.5f)[0];
    row += fmt::format(" {:.1f} / {:.1f} |", 100.0 * lambert.mean, 100.0 * lambert.median);
    normRow += " |";
    for (float r : roughnesses) {
      const std::array<Error, 2> e = measure(types[k], true, r);
      row += fmt::format(" {:.1f} / {:.1f} |", 100.0 * e[0].mean, 100.0 * e[0].median);
      normRow += fmt::format(" {:.1f} / {:.1f} |", 100.0 * e[1].mean, 100.0 * e[1].median);
    }
    fmt::print("{}\n", row);
    normRows.push_back(normRow);
    std::fflush(stdout);
  }
  fmt::print("\nthe metal with the LTC table's norm and Fresnel term instead of the DFG table's\n");
  for (const std::string& row : normRows) fmt::print("{}\n", row);
  return 0;
}
