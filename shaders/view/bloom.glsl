// The window's bloom (src/gpu/bloom.cpp): applyBloom of src/render/bloom.cpp as compute passes
// over one storage buffer of RGBA32F texels (the chain), levels addressed by their first texel.
// Texel 0 holds the renormalization's per-channel scale, texels 1 .. 2 kBloomGroups the sums'
// partials (excess, spread per work group), then the frame, the excess, the pyramid's levels and
// the spread light.
#extension GL_GOOGLE_include_directive : require
#include "ibl/shared/bloom.h"

layout(std430, binding = 0) buffer Chain { vec4 texels[]; };

// Every pass's push constants (32 bytes; the fields each pass reads are named in its file).
layout(push_constant) uniform BloomPass {
  int source;                     // the first texel of the level read
  int target;                     // the first texel of the level written
  int sourceWidth, sourceHeight;  // the level read
  int width, height;              // the level written
  int other;                      // a second level read (-1: none)
  float threshold;                // the excess pass: bloomThreshold(EV100, EC)
} pass;

const int kBloomScale = 0;
const int kBloomPartials = 1;
const int kBloomGroups = 64;  // the sums' first stage: work groups of 256

vec3 chainAt(int level, int levelWidth, int x, int y) {
  return texels[level + y * levelWidth + x].rgb;
}
