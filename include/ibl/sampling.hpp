#pragma once
// Low-discrepancy sequences and the importance sampling of BRDF lobes, shared by the bake,
// the reference renderer and (as constants) the GPU shaders.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace ibl {

// Van der Corput radical inverse in base 2 (bit reversal of i), in [0, 1).
float radicalInverse2(std::uint32_t i);

// Point i of the n-point Hammersley set: (i / n, radicalInverse2(i)).
glm::vec2 hammersley(std::uint32_t i, std::uint32_t n);

// Orthonormal basis whose third column is n (Duff et al. 2017, "Building an Orthonormal
// Basis, Revisited", JCGT 6(1)); continuous everywhere but at n.z = -1 exactly.
glm::mat3 tangentFrame(glm::vec3 n);

// Half vector distributed with pdf D(h) (n.h) for GGX of parameter alpha, in the tangent
// frame (z = n). Walter et al. 2007, eq. 35-36: cos^2 theta = (1 - u) / (1 + (alpha^2 - 1) u).
glm::vec3 sampleGgxHalfVector(glm::vec2 xi, float alpha);

// Point of the unit disk, uniform in area: (sqrt(u1) cos 2 pi u2, sqrt(u1) sin 2 pi u2).
glm::vec2 uniformDiskPoint(glm::vec2 xi);

// GGX normals visible from direction v (tangent frame, v.z > 0), distributed with pdf
// G1(v) max(0, v.h) D(h) / (n.v): Heitz 2018, "Sampling the GGX Distribution of Visible
// Normals", listing 1 (isotropic). Reflecting v about one gives l with pdf G1 D / (4 n.v).
// The view-dependent part is computed once; sample() maps a uniform disk point to a normal.
class GgxVisibleNormalSampler {
 public:
  GgxVisibleNormalSampler(glm::vec3 v, float alpha);
  // Warps the disk onto the projection of the visible hemisphere, lifts it, unstretches.
  glm::vec3 sample(glm::vec2 disk) const {
    const float p1 = disk.x;
    const float p2 = (1.0f - s_) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s_ * disk.y;
    const glm::vec3 nh =
        p1 * t1_ + p2 * t2_ + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh_;
    return glm::normalize(glm::vec3(alpha_ * nh.x, alpha_ * nh.y, std::max(0.0f, nh.z)));
  }

 private:
  glm::vec3 vh_, t1_, t2_;
  float alpha_, s_;
};
glm::vec3 sampleGgxVisibleNormal(glm::vec3 v, glm::vec2 xi, float alpha);

// Direction with pdf cos(theta) / pi in the tangent frame (Malley's method).
glm::vec3 sampleCosineHemisphere(glm::vec2 xi);

}  // namespace ibl
