#pragma once
// API: internal (may change without notice; math shared with the shaders)
// Low-discrepancy sequences, tangent frames and the importance sampling of BRDF lobes, shared
// by the bake, the reference renderer and the compute shaders: defined once for C++ and GLSL
// in ibl/shared/sampling.h (Hammersley points, Duff et al.'s frame, Walter et al.'s GGX
// half-vector sampling, Heitz 2018's visible normals, Malley's cosine sampling).
#include <cstdint>

#include <glm/vec2.hpp>

#include "ibl/shared/path_sampler.h"
#include "ibl/shared/sampling.h"

namespace ibl {

using shared::hammersley;
using shared::radicalInverse2;
using shared::sampleCosineHemisphere;
using shared::sampleGgxHalfVector;
using shared::sampleGgxVisibleNormal;
using shared::tangentFrame;
using shared::uniformDiskPoint;
using shared::VisibleNormalFrame;
using shared::visibleNormalFrame;
using shared::visibleNormalFromDisk;

// The reference's numbers (ibl/shared/path_sampler.h): an avalanching 32-bit hash (Wellons'
// lowbias32), hash-based Owen scrambling (Burley 2020, "Practical Hash-based Owen Scrambling",
// JCGT 9(4), listing 2: the Laine-Karras permutation between two bit reversals), and point
// `index` of the first two dimensions of the Sobol sequence (a (0,2)-sequence in base 2: every
// prefix of 2^k points has one point in each of the 2^k elementary intervals of any shape),
// shuffled and Owen-scrambled with `seed` (section 4), in [0, 1)^2: any prefix is well
// distributed, and different seeds (pixels) are decorrelated.
using shared::hash32;
using shared::owenScramble;
inline glm::vec2 sobolOwen2D(std::uint32_t index, std::uint32_t seed) {
  return shared::sobolOwenPair(index, seed);
}

}  // namespace ibl
