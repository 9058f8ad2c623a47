#include "ibl/render/light_sampling.hpp"

#include <limits>

#include <glm/geometric.hpp>

#include "ibl/shared/light_sampling.h"

namespace ibl {

namespace {
constexpr float kInfinity = std::numeric_limits<float>::infinity();
}  // namespace

float lightWindow(const Light& light, glm::vec3 p) {
  return shared::lightRangeWindow(shadingLightOf(light), p);
}

LightSample sampleLight(const Light& l, glm::vec3 p, glm::vec2 xi) {
  const shared::ShadingLight shading = shadingLightOf(l);
  LightSample s;
  if (l.type == LightType::Point || l.type == LightType::Spot) {
    const glm::vec3 d = l.position - p;
    s.distance = glm::length(d);
    s.direction = d / s.distance;
    s.delta = true;
    s.radiance =
        l.color * l.intensityToward(-s.direction) * shared::punctualLightIrradiance(shading, p);
    return s;
  }
  const shared::AreaLightSample a = shared::sampleAreaLight(shading, p, xi);
  s.direction = a.direction;
  s.distance = a.distance == shared::kSunDistance ? kInfinity : a.distance;
  s.pdf = a.pdf;
  s.radiance = a.radiance * shared::lightRangeWindow(shading, p);
  return s;
}

float lightPdf(const Light& l, glm::vec3 p, glm::vec3 w) {
  return shared::areaLightPdf(shadingLightOf(l), p, w);
}

std::optional<LightHit> intersectLight(const Light& l, glm::vec3 p, glm::vec3 w) {
  const shared::ShadingLight s = shadingLightOf(l);
  const float t = shared::emitterDistance(s, p, w);
  if (t < 0.0f) return std::nullopt;
  return LightHit{t == shared::kSunDistance ? kInfinity : t, shared::emitterRadiance(s, w)};
}

}  // namespace ibl
