#include "ibl/render/light_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "ibl/math/sampling.hpp"

namespace ibl {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// --- Spherical caps: the sun and spheres ---

struct Cap {
  glm::vec3 axis;        // unit, toward the cap's center
  float oneMinusCosMax;  // 1 - cos(half-angle), written to keep small caps exact
  bool valid;
};

Cap sphereCap(const Light& l, glm::vec3 p) {
  const glm::vec3 c = l.position - p;
  const float d2 = glm::dot(c, c);
  const float sin2 = l.radius * l.radius / d2;
  if (!(sin2 < 1.0f)) return {glm::vec3(0.0f), 0.0f, false};  // inside the sphere
  return {c / std::sqrt(d2), sin2 / (1.0f + std::sqrt(1.0f - sin2)), true};
}

Cap sunCap(const Light& l) {
  const float s = std::sin(0.5f * l.angularDiameter);
  const float sin2 = s * s;
  return {l.direction, sin2 / (1.0f + std::sqrt(1.0f - sin2)), true};
}

// Uniform in the cap (pbrt-v4 4th ed., section 12.2.3): cos(theta) uniform in [cos max, 1].
glm::vec3 sampleCap(const Cap& cap, glm::vec2 xi) {
  const float oneMinusCos = xi.x * cap.oneMinusCosMax;
  const float cosTheta = 1.0f - oneMinusCos;
  const float sinTheta = std::sqrt(std::max(0.0f, oneMinusCos * (2.0f - oneMinusCos)));
  const float phi = 2.0f * kPi * xi.y;
  return glm::normalize(tangentFrame(cap.axis) *
                        glm::vec3(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta));
}

float capPdf(const Cap& cap) {
  return 1.0f / (2.0f * kPi * cap.oneMinusCosMax);
}

bool inCap(const Cap& cap, glm::vec3 w) {
  return 1.0f - glm::dot(cap.axis, w) <= cap.oneMinusCosMax;
}

// The sun's luminance from its illuminance: E = L pi sin^2(sigma) on a surface facing it.
float sunLuminance(const Light& l) {
  const float s = std::sin(0.5f * l.angularDiameter);
  return l.intensity / (kPi * s * s);
}

// --- Ray and shape intersections (ibl/shared/lights.h, which the viewer uses too), a miss as
// infinity ---

float finiteOrInfinity(float t) {
  return t >= 0.0f ? t : kInfinity;
}

float raySphere(glm::vec3 o, glm::vec3 w, glm::vec3 center, float radius) {
  return finiteOrInfinity(shared::raySphereDistance(o, w, center, radius));
}

// A capsule: the segment c +- axis length/2, radius r; `normal`: the surface's at the hit.
float rayCapsule(glm::vec3 o, glm::vec3 w, const Light& l, glm::vec3* normal) {
  const float t = finiteOrInfinity(
      shared::rayCapsuleDistance(o, w, l.position, l.direction, l.length, l.radius));
  if (normal && std::isfinite(t)) {
    const glm::vec3 q = o + t * w - l.position;
    const float along = std::clamp(glm::dot(q, l.direction), -0.5f * l.length, 0.5f * l.length);
    *normal = glm::normalize(q - along * l.direction);
  }
  return t;
}

glm::vec3 rectLeft(const Light& l) {
  return glm::cross(l.up, l.direction);
}

// --- Spherical rectangles (Urena, Fajardo & King 2013, "An Area-Preserving Parametrization for
// Spherical Rectangles", sections 3-4) ---

struct SphericalRect {
  glm::vec3 o, x, y, z;  // reference point and the local frame (z points away from the rect)
  float x0, x1, y0, y1, z0;
  float b0, b1, k, solidAngle;
};

SphericalRect sphericalRect(glm::vec3 p, glm::vec3 s, glm::vec3 ex, glm::vec3 ey) {
  SphericalRect r;
  r.o = p;
  const float exl = glm::length(ex), eyl = glm::length(ey);
  r.x = ex / exl;
  r.y = ey / eyl;
  r.z = glm::cross(r.x, r.y);
  const glm::vec3 d = s - p;
  r.z0 = glm::dot(d, r.z);
  if (r.z0 > 0.0f) {  // the frame's z must point away from the rectangle
    r.z = -r.z;
    r.z0 = -r.z0;
  }
  r.x0 = glm::dot(d, r.x);
  r.y0 = glm::dot(d, r.y);
  r.x1 = r.x0 + exl;
  r.y1 = r.y0 + eyl;
  const glm::vec3 v00(r.x0, r.y0, r.z0), v01(r.x0, r.y1, r.z0), v10(r.x1, r.y0, r.z0),
      v11(r.x1, r.y1, r.z0);
  const glm::vec3 n0 = glm::normalize(glm::cross(v00, v10)),
                  n1 = glm::normalize(glm::cross(v10, v11)),
                  n2 = glm::normalize(glm::cross(v11, v01)),
                  n3 = glm::normalize(glm::cross(v01, v00));
  const auto angle = [](glm::vec3 a, glm::vec3 b) {
    return std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f));
  };
  const float g0 = angle(-n0, n1), g1 = angle(-n1, n2), g2 = angle(-n2, n3), g3 = angle(-n3, n0);
  r.b0 = n0.z;
  r.b1 = n2.z;
  r.k = 2.0f * kPi - g2 - g3;
  r.solidAngle = g0 + g1 - r.k;
  return r;
}

glm::vec3 sampleSphericalRect(const SphericalRect& r, glm::vec2 xi) {
  const float au = xi.x * r.solidAngle + r.k;
  const float fu = (std::cos(au) * r.b0 - r.b1) / std::sin(au);
  float cu = std::copysign(1.0f, fu) / std::sqrt(fu * fu + r.b0 * r.b0);
  cu = std::clamp(cu, -0.99999994f, 0.99999994f);
  float xu = -(cu * r.z0) / std::sqrt(std::max(0.0f, 1.0f - cu * cu));
  xu = std::clamp(xu, r.x0, r.x1);
  const float d = std::sqrt(xu * xu + r.z0 * r.z0);
  const float h0 = r.y0 / std::sqrt(d * d + r.y0 * r.y0),
              h1 = r.y1 / std::sqrt(d * d + r.y1 * r.y1);
  const float hv = h0 + xi.y * (h1 - h0), hv2 = hv * hv;
  const float yv = hv2 < 1.0f - 1e-6f ? hv * d / std::sqrt(1.0f - hv2) : r.y1;
  return r.o + xu * r.x + yv * r.y + r.z0 * r.z;
}

SphericalRect rectSeenFrom(const Light& l, glm::vec3 p) {
  const glm::vec3 left = rectLeft(l);
  const glm::vec3 s = l.position - 0.5f * l.width * left - 0.5f * l.height * l.up;
  return sphericalRect(p, s, l.width * left, l.height * l.up);
}

// Area sampling's density per solid angle: d^2 / (A cos), 0 from the back.
float areaPdf(glm::vec3 w, float distance, glm::vec3 surfaceNormal, float area) {
  const float cosLight = -glm::dot(surfaceNormal, w);
  if (!(cosLight > 0.0f)) return 0.0f;
  return distance * distance / (area * cosLight);
}

float capsuleArea(const Light& l) {
  return 2.0f * kPi * l.radius * l.length + 4.0f * kPi * l.radius * l.radius;
}

}  // namespace

float lightWindow(const Light& light, glm::vec3 p) {
  if (light.range <= 0.0f || light.type == LightType::Sun) return 1.0f;
  const glm::vec3 d = light.position - p;
  return shared::smoothDistanceWindow(glm::dot(d, d), 1.0f / (light.range * light.range));
}

LightSample sampleLight(const Light& l, glm::vec3 p, glm::vec2 xi) {
  LightSample s;
  const glm::vec3 luminance = l.color * l.intensity * lightWindow(l, p);
  switch (l.type) {
    case LightType::Point:
    case LightType::Spot: {
      const glm::vec3 d = l.position - p;
      const float d2 = glm::dot(d, d);
      s.direction = d / std::sqrt(d2);
      s.distance = std::sqrt(d2);
      s.delta = true;
      const float invR2 = l.range > 0.0f ? 1.0f / (l.range * l.range) : 0.0f;
      float e = l.intensityToward(-s.direction) * shared::distanceAttenuation(d2, invR2);
      if (l.type == LightType::Spot)
        e *= shared::spotAngleAttenuation(glm::dot(l.direction, -s.direction),
                                          std::cos(l.innerAngle), std::cos(l.outerAngle));
      s.radiance = l.color * e;
      return s;
    }
    case LightType::Sun: {
      const Cap cap = sunCap(l);
      s.direction = sampleCap(cap, xi);
      s.distance = kInfinity;
      s.radiance = l.color * sunLuminance(l);
      s.pdf = capPdf(cap);
      return s;
    }
    case LightType::Sphere: {
      const Cap cap = sphereCap(l, p);
      if (!cap.valid) return s;
      s.direction = sampleCap(cap, xi);
      s.distance = raySphere(p, s.direction, l.position, l.radius);
      if (!std::isfinite(s.distance)) s.distance = glm::length(l.position - p);  // grazing
      s.radiance = luminance;
      s.pdf = capPdf(cap);
      return s;
    }
    case LightType::Disk: {
      const glm::mat3 frame = tangentFrame(l.direction);
      const float rho = l.radius * std::sqrt(xi.x), phi = 2.0f * kPi * xi.y;
      const glm::vec3 q =
          l.position + frame * glm::vec3(rho * std::cos(phi), rho * std::sin(phi), 0.0f);
      const glm::vec3 d = q - p;
      s.distance = glm::length(d);
      s.direction = d / s.distance;
      s.pdf = areaPdf(s.direction, s.distance, l.direction, kPi * l.radius * l.radius);
      if (s.pdf > 0.0f) s.radiance = luminance;
      return s;
    }
    case LightType::Rect: {
      const SphericalRect r = rectSeenFrom(l, p);
      if (!(r.solidAngle > 1e-9f)) return s;
      const glm::vec3 q = sampleSphericalRect(r, xi);
      const glm::vec3 d = q - p;
      s.distance = glm::length(d);
      s.direction = d / s.distance;
      s.pdf = 1.0f / r.solidAngle;
      if (glm::dot(p - l.position, l.direction) > 0.0f) s.radiance = luminance;
      return s;
    }
    case LightType::Tube: {
      const float area = capsuleArea(l);
      const float cylinder = 2.0f * kPi * l.radius * l.length / area;
      const glm::mat3 frame = tangentFrame(l.direction);
      glm::vec3 q, normal;
      if (xi.x < cylinder) {
        const float z = (xi.x / cylinder - 0.5f) * l.length, phi = 2.0f * kPi * xi.y;
        normal = frame * glm::vec3(std::cos(phi), std::sin(phi), 0.0f);
        q = l.position + z * l.direction + l.radius * normal;
      } else {
        const float u = (xi.x - cylinder) / (1.0f - cylinder);
        const float cosTheta = 1.0f - 2.0f * std::min(u, 1.0f);
        const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
        const float phi = 2.0f * kPi * xi.y;
        normal = frame * glm::vec3(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
        const float end = cosTheta >= 0.0f ? 0.5f * l.length : -0.5f * l.length;
        q = l.position + end * l.direction + l.radius * normal;
      }
      const glm::vec3 d = q - p;
      s.distance = glm::length(d);
      s.direction = d / s.distance;
      s.pdf = areaPdf(s.direction, s.distance, normal, area);
      if (s.pdf > 0.0f) s.radiance = luminance;
      return s;
    }
  }
  return s;
}

float lightPdf(const Light& l, glm::vec3 p, glm::vec3 w) {
  switch (l.type) {
    case LightType::Point:
    case LightType::Spot:
      return 0.0f;
    case LightType::Sun: {
      const Cap cap = sunCap(l);
      return inCap(cap, w) ? capPdf(cap) : 0.0f;
    }
    case LightType::Sphere: {
      const Cap cap = sphereCap(l, p);
      return cap.valid && inCap(cap, w) ? capPdf(cap) : 0.0f;
    }
    case LightType::Disk: {
      const float t = shared::emitterDistance(shadingLightOf(l), p, w);
      if (t < 0.0f) return 0.0f;
      return areaPdf(w, t, l.direction, kPi * l.radius * l.radius);
    }
    case LightType::Rect: {
      if (shared::emitterDistance(shadingLightOf(l), p, w) < 0.0f) return 0.0f;
      const SphericalRect r = rectSeenFrom(l, p);
      return r.solidAngle > 1e-9f ? 1.0f / r.solidAngle : 0.0f;
    }
    case LightType::Tube: {
      glm::vec3 normal;
      const float t = rayCapsule(p, w, l, &normal);
      if (!std::isfinite(t)) return 0.0f;
      return areaPdf(w, t, normal, capsuleArea(l));
    }
  }
  return 0.0f;
}

std::optional<LightHit> intersectLight(const Light& l, glm::vec3 p, glm::vec3 w) {
  const shared::ShadingLight s = shadingLightOf(l);
  const float t = shared::emitterDistance(s, p, w);
  if (t < 0.0f) return std::nullopt;
  return LightHit{t == shared::kSunDistance ? kInfinity : t, shared::emitterRadiance(s, w)};
}

}  // namespace ibl
