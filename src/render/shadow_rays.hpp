#pragma once
// Internal to the renderer: the exact visibility that ShadowMode::Ray gives the CPU split sum.
#include <glm/vec3.hpp>

#include "ibl/render/light.hpp"

namespace ibl {

class RayTracer;
class Sampler;
struct Scene;

// The share of light that crosses the segment from `origin` along unit `direction` for
// `distance` in a straight line: 0 behind a surface that transmits nothing; through surfaces
// that transmit, the product of shared::surfaceShadowTransmittance at each and Beer-Lambert over
// the chords of the volumes it crosses (KHR_materials_volume).
glm::vec3 straightTransmittance(const Scene& scene, const RayTracer& tracer, glm::vec3 origin,
                                glm::vec3 direction, float distance);

// The same where nothing opaque lies on the segment (a segment that ends at the first opaque
// surface): the surfaces that transmit alone.
glm::vec3 transmissiveTransmittance(const Scene& scene, const RayTracer& tracer, glm::vec3 origin,
                                    glm::vec3 direction, float distance);

// The share of the light's irradiance at p (normal n) that arrives, per channel, estimated from
// `samples` stratified samples of the light (sampleLight; one for punctual lights), each traced
// to the sampled point (the sun: to infinity; straightTransmittance where the scene transmits)
// and weighed by radiance x cosine / density. 1 when no sample reaches p.
glm::vec3 rayTracedVisibility(const Scene& scene, const RayTracer& tracer, const Light& light,
                              glm::vec3 p, glm::vec3 n, int samples, Sampler& sampler);

}  // namespace ibl
