#pragma once
// The table of linearly transformed cosines (ibl/shared/ltc.h) that the real-time area lights
// read for the GGX lobe, and the fitter that computes it. The table is the project's own fit:
// `ibl_ltc_fit` (tools/ltc_fit.cpp) runs fitLtcTable and writes src/render/ltc_table.inc, with
// the fit error it reached in its header.
//
// The fit follows Heitz et al. 2016, section 4: for each GGX alpha and view angle, the target is
// the lobe D(h) G2(v, l) / (4 n.v), with no Fresnel, normalized to integrate to 1 over the
// hemisphere (its magnitude, with Fresnel, is the DFG table's F0 A + B); the LTC is
// M = R(phi) [[m11, 0, m13], [0, m22, 0], [m31, 0, 1]], R the rotation about y that takes z to
// the lobe's mean direction, and (m11, m22, m13, m31) minimize the integral of |target - LTC|^3,
// estimated with samples of both distributions (multiple importance sampling), by Nelder-Mead from
// the previous view angle's fit.
#include <functional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace ibl {

// The table as shipped: size x size entries (M^-1 as ltc.h stores it), entry(column, row) at
// entries[row * size + column], column j at perceptual roughness j / (size - 1), row i at
// sqrt(1 - n.v) = i / (size - 1) (ltcTableCoordinates).
struct LtcTable {
  int size = 0;
  std::span<const glm::vec4> entries;
};
const LtcTable& ltcGgxTable();

// The table's entry at (perceptual roughness, n.v), interpolated bilinearly between texel
// centers and clamped at the edges: what the viewer's sampler returns for the same table.
glm::vec4 ltcTableLookup(float roughness, float NoV);

// The GGX alpha a column of a table of `size` fits (the square of its roughness, at least the
// shading's smallest alpha) and the n.v a row fits.
float ltcColumnAlpha(int column, int size);
float ltcRowCosTheta(int row, int size);

struct LtcFit {
  glm::vec4 entry{1.0f, 0.0f, 0.0f, 1.0f};       // M^-1 as ltc.h stores it
  glm::vec4 parameters{1.0f, 1.0f, 0.0f, 0.0f};  // (m11, m22, m13, m31)
  float error = 0.0f;                            // ltcFitError of the entry
};

// Fits the LTC of GGX `alpha` seen at n.v = cosTheta, Nelder-Mead starting from `start`
// (m11, m22, m13, m31: a neighbouring fit's parameters, or (alpha, alpha, 0, 0)).
LtcFit fitLtc(float alpha, float cosTheta, glm::vec4 start);

// The L1 distance between the normalized GGX lobe and the LTC `entry`, the integral over the
// sphere of |target - LTC| (0: identical, 2: disjoint), by multiple importance sampling with
// `samples`^2 directions from each.
float ltcFitError(glm::vec4 entry, float alpha, float cosTheta, int samples = 128);

// Fits a table of size x size entries (columns in parallel; each column from n.v = 1 toward
// grazing). progress(fraction) is called as columns finish.
std::vector<LtcFit> fitLtcTable(int size, const std::function<void(float)>& progress = {});

}  // namespace ibl
