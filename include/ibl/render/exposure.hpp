#pragma once
// API: internal (may change without notice; the viewer's auto exposure)
// Auto exposure as engines meter it: a histogram of the frame's log2 luminance
// (ibl/shared/exposure.h: 256 bins of 1/8 stop from 2^-12 to 2^20 cd/m^2), the darkest and
// brightest pixels left out (percentiles, as Unreal's, Unity HDRP's and Flax's eye adaptation
// do), the log-average of the rest exposed for middle gray with Lagarde & de Rousiers 2014's
// computeEV100FromAvgLuminance (ev100FromAverageLuminance, camera.hpp), and the exposure eased
// toward it frame by frame.
#include <array>
#include <cstdint>

#include "ibl/core/image.hpp"
#include "ibl/shared/exposure.h"

namespace ibl {

// Pixel counts per bin of log2 luminance (shared::luminanceBin); pixels of zero luminance, or
// not finite, are not counted.
using LuminanceHistogram = std::array<std::uint32_t, shared::kLuminanceBins>;

// The histogram of `linear`'s Rec.709 luminance (cd/m^2 for a render).
LuminanceHistogram luminanceHistogram(const Image& linear);

// The share of the metered pixels auto exposure reads: those between the `low` and `high`
// percentiles of luminance (0 <= low < high <= 100).
struct MeteringRange {
  float low = 10.0f;
  float high = 90.0f;
};

// The log-average luminance (2^(mean log2 L)) of the pixels between range.low and range.high
// percent of the histogram's total count, each bin at its center's luminance and the bins cut by
// a percentile counted in part; 0 when the histogram is empty.
float meteredLuminance(const LuminanceHistogram& histogram, MeteringRange range);

// The EV100 the frame's histogram asks for: ev100FromAverageLuminance(meteredLuminance(...));
// none (0 pixels metered) gives `fallback`.
float meteredEv100(const LuminanceHistogram& histogram, MeteringRange range, float fallback);

// Eye adaptation: `current` eased toward `target` over `seconds` at `speed` (1/s), exponentially:
// target + (current - target) e^(-speed seconds). Steps of any length compose (two steps of t are
// one of 2t), so the exposure settles at the same pace at any frame rate; speed <= 0 jumps.
float adaptEv100(float current, float target, float seconds, float speed);

}  // namespace ibl
