// API: internal (may change without notice; math shared with the shaders)
// Temporal antialiasing of the viewer (shaders/view/temporal_resolve.comp, src/gpu/
// temporal_pass.cpp): each frame is drawn with its projection shifted by a sub-pixel jitter,
// and blended into a history of the frames before it, reprojected through the camera's motion
// and clipped to the range of the frame's own neighborhood, after Karis 2014, "High Quality
// Temporal Supersampling" (SIGGRAPH course Advances in Real-Time Rendering). C++ and GLSL (see
// lang.h).
#ifndef IBL_SHARED_TEMPORAL_ANTIALIASING_H
#define IBL_SHARED_TEMPORAL_ANTIALIASING_H
#include "ibl/shared/cube.h"  // catmullRomWeights, the history's resampling filter
#include "ibl/shared/lang.h"

IBL_BEGIN

// The jitters the window cycles through (Karis uses 8; 16 covers a pixel more evenly).
const int kTemporalJitterPeriod = 16;
// The share of each new frame in the window's history: the exponential moving average of Karis
// 2014 (0.04 to 0.1 there); the rest is the reprojected, clipped history.
const float kTemporalFeedback = 0.1f;

// The radical inverse of `index` in `base`: its digits mirrored about the radix point
// (van der Corput), the coordinate of the Halton sequence in that base.
IBL_FN float radicalInverse(int index, int base) {
  float inverse = 1.0f / float(base), scale = inverse, value = 0.0f;
  for (int i = index; i > 0; i /= base) {
    value += float(i % base) * scale;
    scale *= inverse;
  }
  return value;
}

// The sub-pixel offset of frame `index` (0, 1, ...), in pixels within (-0.5, 0.5)^2: point
// index + 1 of the Halton sequence in bases 2 and 3 (point 0 is the origin), centered on the
// pixel. Any run of frames spreads over the pixel with low discrepancy, so that their average
// is the pixel's box-filtered value.
IBL_FN vec2 temporalJitter(int index) {
  return vec2(radicalInverse(index + 1, 2), radicalInverse(index + 1, 3)) - 0.5f;
}

// RGB to YCoCg, the space the neighborhood's box is taken in (Karis 2014: luma apart from
// chroma makes a tighter box), and back. Y = R/4 + G/2 + B/4, Co = R/2 - B/2,
// Cg = -R/4 + G/2 - B/4.
IBL_FN vec3 rgbToYCoCg(vec3 c) {
  return vec3(0.25f * c.x + 0.5f * c.y + 0.25f * c.z, 0.5f * c.x - 0.5f * c.z,
              -0.25f * c.x + 0.5f * c.y - 0.25f * c.z);
}
IBL_FN vec3 yCoCgToRgb(vec3 c) {
  return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
}

// The history clipped to the box [boxMin, boxMax] of the frame's neighborhood: where it lies
// outside, the point where the segment from `center` (inside the box) to it leaves the box;
// inside, the history itself (Karis 2014: clipping toward the center rather than clamping each
// channel keeps the color's hue).
IBL_FN vec3 clipToBox(vec3 history, vec3 boxMin, vec3 boxMax, vec3 center) {
  vec3 toHistory = history - center;
  vec3 halfExtent = max(0.5f * (boxMax - boxMin), vec3(1e-7f));
  vec3 boxCenter = 0.5f * (boxMax + boxMin);
  // The largest t in [0, 1] with center + t toHistory in the box, per axis.
  float t = 1.0f;
  for (int i = 0; i < 3; ++i) {
    float d = toHistory[i];
    if (abs(d) > 1e-12f) {
      float limit = (d > 0.0f ? boxCenter[i] + halfExtent[i] : boxCenter[i] - halfExtent[i]);
      t = min(t, max((limit - center[i]) / d, 0.0f));
    }
  }
  return center + t * toHistory;
}

// The blend of the frame's `current` color into the clipped `history` with the new frame's
// share `feedback`, each weighted by 1 / (1 + its displayed luma) (Karis 2014: so that a
// lone bright sample, which the display clips, does not flicker through the average).
// `exposure` turns radiance into the display's range.
IBL_FN vec4 temporalBlend(vec4 current, vec4 history, float feedback, float exposure) {
  float currentWeight = feedback / (1.0f + exposure * rgbToYCoCg(vec3(current)).x);
  float historyWeight = (1.0f - feedback) / (1.0f + exposure * rgbToYCoCg(vec3(history)).x);
  return (currentWeight * current + historyWeight * history) / (currentWeight + historyWeight);
}

IBL_END

#endif
