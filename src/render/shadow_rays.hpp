#pragma once
// Internal to the renderer: the exact visibility that ShadowMode::Ray gives the CPU split sum.
#include <glm/vec3.hpp>

#include "ibl/render/light.hpp"

namespace ibl {

class RayTracer;
class Sampler;

// The share of the light's irradiance at p (normal n) that arrives unoccluded, estimated from
// `samples` stratified samples of the light (sampleLight; one for punctual lights), each traced
// to the sampled point (the sun: to infinity) and weighed by radiance x cosine / density.
// 1 when no sample reaches p.
float rayTracedVisibility(const RayTracer& tracer, const Light& light, glm::vec3 p, glm::vec3 n,
                          int samples, Sampler& sampler);

}  // namespace ibl
