#pragma once
// API: internal (may change without notice; renderer internals behind render/renderer.hpp)
// The table of linearly transformed cosines (ibl/shared/ltc.h) that the real-time area lights
// read for the GGX lobe, and the fitter that computes it. The table is the project's own fit:
// `ibl_ltc_fit` (tools/ltc_fit.cpp) runs fitLtcTable and writes src/render/ltc_table.inc, with
// the fit error it reached in its header.
//
// The fit follows Heitz et al. 2016, section 4, and their fitting code (fitLTC.cpp), written anew:
// for each GGX alpha and view angle, the target is the lobe D(h) G2(v, l) / (4 n.v), with no
// Fresnel, normalized to integrate to 1 over the hemisphere; the LTC is
// M = R(phi) [[m11, 0, m13], [0, m22, 0], [m31, 0, 1]], R the rotation about y that takes z to
// the lobe's mean direction, and (m11, m22, m13, m31) minimize the integral of |target - LTC|
// (Heitz's objective is the integral of its cube; the first power holds the tails closer),
// estimated with 32^2 samples of each distribution (the BRDF's and the LTC's) combined by the
// balance heuristic, by Nelder-Mead. Initialization as theirs: the row at n.v = 1 is isotropic
// (m11 = m22, no rotation), fitted from the roughest column (the cosine) toward the smoothest,
// each from its neighbour; each other row from the previous row's fit. Beside M^-1 the table
// holds the lobe's norm, Fresnel term and mean direction (LtcNorm; their second table).
#include <functional>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace ibl {

// The table as shipped: size x size entries (M^-1 as ltc.h stores it), entry(column, row) at
// entries[row * size + column], column j at perceptual roughness j / (size - 1), row i at
// sqrt(1 - n.v) = i / (size - 1) (ltcTableCoordinates); norms, at the same places, the lobe's
// (norm, Fresnel term, mean direction x, z) as LtcNorm holds them (ltc.h's second texture).
struct LtcTable {
  int size = 0;
  std::span<const glm::vec4> entries;
  std::span<const glm::vec4> norms;
};
// The fitted table compiled into the library (static storage).
const LtcTable& ltcGgxTable();

// The table's entry at (perceptual roughness, n.v), interpolated bilinearly between texel
// centers and clamped at the edges: what the viewer's sampler returns for the same table.
glm::vec4 ltcTableLookup(float roughness, float NoV);
// The same for the second table: (norm, Fresnel term, mean direction x, z).
glm::vec4 ltcNormLookup(float roughness, float NoV);

// The GGX lobe's averaged terms (Heitz et al. 2016's second table; their computeAvgTerms): the
// norm, the integral of rho cos over the hemisphere without Fresnel; the Fresnel term, the same
// weighted by (1 - v.h)^5 (the lobe with Schlick's Fresnel integrates to
// F0 (norm - fresnel) + f90 fresnel: the DFG table's A = norm - fresnel, B = fresnel); the mean
// direction (x, z), the integral of rho cos l over the norm (its length below 1: the lobe's
// spread, the length of its form factor vector over its norm).
struct LtcNorm {
  float norm = 1.0f;
  float fresnel = 0.0f;
  glm::vec2 meanDirection{0.0f, 1.0f};
};
// By importance sampling the lobe with samples^2 stratified directions.
LtcNorm ltcLobeAverages(float alpha, float cosTheta, int samples = 128);

// The GGX alpha a column of a table of `size` fits (the square of its roughness, at least the
// shading's smallest alpha) and the n.v a row fits.
float ltcColumnAlpha(int column, int size);
float ltcRowCosTheta(int row, int size);

struct LtcFit {
  glm::vec4 entry{1.0f, 0.0f, 0.0f, 1.0f};       // M^-1 as ltc.h stores it
  glm::vec4 parameters{1.0f, 1.0f, 0.0f, 0.0f};  // (m11, m22, m13, m31)
  LtcNorm norm;                                  // the lobe's averaged terms
  float error = 0.0f;                            // ltcFitError of the entry
};

struct LtcFitOptions {
  int samples = 32;  // the objective's samples, samples^2 of each distribution (Heitz's 32)
  // The objective: the integral of |target - LTC|^exponent. Heitz's is 3; 1 holds the lobe's
  // tails closer (docs/lights.md, "The LTC table and its fit") and made the shipped table.
  int exponent = 1;
};

// Fits the LTC of GGX `alpha` seen at n.v = cosTheta, Nelder-Mead starting from `start`
// (m11, m22, m13, m31: a neighbouring fit's parameters, or (alpha, alpha, 0, 0)); isotropic:
// m11 = m22 (start.x), m13 = m31 = 0, no rotation (the lobe at n.v = 1).
LtcFit fitLtc(float alpha, float cosTheta, glm::vec4 start, bool isotropic = false,
              const LtcFitOptions& options = {});

// The L1 distance between the normalized GGX lobe and the LTC `entry`, the integral over the
// sphere of |target - LTC| (0: identical, 2: disjoint), by multiple importance sampling with
// `samples`^2 directions from each.
float ltcFitError(glm::vec4 entry, float alpha, float cosTheta, int samples = 128);

// Fits a table of size x size entries: the row at n.v = 1 (isotropic) from the roughest column to
// the smoothest, then the columns in parallel, each from n.v = 1 toward grazing.
// progress(fraction) is called as columns finish.
std::vector<LtcFit> fitLtcTable(int size, const std::function<void(float)>& progress = {},
                                const LtcFitOptions& options = {});

}  // namespace ibl
