#pragma once
// Low-discrepancy sequences, tangent frames and the importance sampling of BRDF lobes, shared
// by the bake, the reference renderer and the compute shaders: defined once for C++ and GLSL
// in ibl/shared/sampling.h (Hammersley points, Duff et al.'s frame, Walter et al.'s GGX
// half-vector sampling, Heitz 2018's visible normals, Malley's cosine sampling).
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

}  // namespace ibl
