#version 450
// Temporal antialiasing (src/gpu/temporal_pass.cpp, ibl/shared/temporal_antialiasing.h): a
// frame drawn with a jittered projection blended into the history of those before it. Per
// pixel: the surface the pixel shows (its view-space position, or the sky's direction) is
// projected by the previous frame's camera; the history is read there with a Catmull-Rom
// filter, clipped in YCoCg to the box of the frame's 3 x 3 neighborhood, and blended with the
// frame (Karis 2014). Accumulation (a still camera, the frames of a screenshot) averages the
// frames instead, each with weight 1 / count, unclipped.
#extension GL_GOOGLE_include_directive : require
#include "ibl/shared/temporal_antialiasing.h"
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer Current { vec4 current[]; };      // this frame
layout(std430, binding = 1) readonly buffer Positions { vec4 positions[]; };  // view space, w 1
layout(std430, binding = 2) readonly buffer HistoryIn { vec4 historyIn[]; };
layout(std430, binding = 3) writeonly buffer HistoryOut { vec4 historyOut[]; };
layout(std430, binding = 4) readonly buffer Parameters {
  mat4 previousViewProjection;  // the previous frame's camera with this frame's jitter
  vec4 cameraPosition;          // w 1 perspective
  vec4 cameraRight;             // scaled as frame.glsl's (the view's half extent)
  vec4 cameraUp;
  vec4 cameraForward;
  vec4 jitter;  // this frame's, in pixels; exposure; the frame's share
  ivec4 size;   // width, height, mode (kTemporal* below), 0
} p;

const int kTemporalFirst = 0;       // no history: the frame itself
const int kTemporalReproject = 1;   // the window's moving average
const int kTemporalAccumulate = 2;  // a still camera's average

// Whether every channel is a finite number (false for NaN and infinities: a pixel of those is
// never carried in the history, which would spread it through the filter).
bool finiteColor(vec4 c) {
  return all(lessThan(abs(c), vec4(3.0e38)));
}

ivec2 frameSize() {
  return p.size.xy;
}

int texel(ivec2 q) {
  ivec2 c = clamp(q, ivec2(0), frameSize() - 1);
  return c.y * frameSize().x + c.x;
}

// The history at pixel coordinates `at` (texel centers at half-integers) through the 4 x 4
// Catmull-Rom filter, clamped to the edges.
vec4 historyAt(vec2 at) {
  vec2 t = at - 0.5;
  vec2 base = floor(t);
  vec4 wx = catmullRomWeights(t.x - base.x), wy = catmullRomWeights(t.y - base.y);  // cube.h
  ivec2 b = ivec2(base) - 1;
  vec4 sum = vec4(0.0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) sum += wx[i] * wy[j] * historyIn[texel(b + ivec2(i, j))];
  return sum;
}

// Where the pixel's surface (or, with none, the sky it shows) was on the previous frame's
// screen, in pixel coordinates.
vec2 previousPixel(ivec2 pixel) {
  vec4 position = positions[texel(pixel)];
  vec4 world;
  if (position.w > 0.5) {
    world = vec4(p.cameraPosition.xyz + position.x * normalize(p.cameraRight.xyz) +
                     position.y * normalize(p.cameraUp.xyz) + position.z * p.cameraForward.xyz,
                 1.0);
  } else {
    // The sky: the pixel's jittered ray (frame.glsl's cameraRay), at infinity in perspective.
    vec2 q = vec2(pixel) + 0.5 - p.jitter.xy;
    float x = 2.0 * q.x / float(frameSize().x) - 1.0;
    float y = 1.0 - 2.0 * q.y / float(frameSize().y);
    vec3 d = p.cameraForward.xyz + x * p.cameraRight.xyz + y * p.cameraUp.xyz;
    world = p.cameraPosition.w > 0.5
                ? vec4(normalize(d), 0.0)
                : vec4(p.cameraPosition.xyz + x * p.cameraRight.xyz + y * p.cameraUp.xyz, 1.0);
  }
  vec4 clip = p.previousViewProjection * world;
  if (!(clip.w > 1e-6)) return vec2(-1.0);  // behind the previous camera: off its screen
  vec2 ndc = clip.xy / clip.w;
  return (0.5 * ndc + 0.5) * vec2(frameSize());
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, frameSize()))) return;
  int i = texel(pixel);
  vec4 color = current[i];
  int mode = p.size.z;
  if (mode == kTemporalFirst) {
    historyOut[i] = color;
    return;
  }
  if (mode == kTemporalAccumulate) {
    historyOut[i] = finiteColor(historyIn[i]) ? mix(historyIn[i], color, p.jitter.w) : color;
    return;
  }
  vec2 at = previousPixel(pixel);
  if (any(lessThan(at, vec2(0.0))) || any(greaterThan(at, vec2(frameSize())))) {
    historyOut[i] = color;  // off the previous screen: no history
    return;
  }
  // The box of the 3 x 3 neighborhood in YCoCg and its mean.
  vec3 boxMin = vec3(1e30), boxMax = vec3(-1e30), mean = vec3(0.0);
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      vec3 c = rgbToYCoCg(current[texel(pixel + ivec2(x, y))].rgb);
      boxMin = min(boxMin, c);
      boxMax = max(boxMax, c);
      mean += c / 9.0;
    }
  vec4 history = historyAt(at);
  if (!finiteColor(color) || !finiteColor(history)) {
    historyOut[i] = color;
    return;
  }
  vec3 clipped = clipToBox(rgbToYCoCg(history.rgb), boxMin, boxMax, mean);
  history = vec4(max(yCoCgToRgb(clipped), vec3(0.0)), clamp(history.a, 0.0, 1.0));
  historyOut[i] = temporalBlend(color, history, p.jitter.w, p.jitter.z);
}
