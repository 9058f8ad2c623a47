#version 450
// Auto exposure's histogram of a frame (src/gpu/exposure.cpp): each pixel's Rec.709 luminance
// counted in its bin of log2 luminance (ibl/shared/exposure.h), as luminanceHistogram counts it on
// the CPU. Each work group counts into shared memory, then adds its counts to the bins.
#extension GL_GOOGLE_include_directive : require
#include "ibl/shared/exposure.h"
layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Frame { vec4 texels[]; };
layout(std430, binding = 1) buffer Bins { uint bins[]; };
layout(push_constant) uniform Push { int count; } push;  // the frame's pixels

shared uint counts[kLuminanceBins];

void main() {
  uint i = gl_LocalInvocationID.x;
  counts[i] = 0u;  // kLuminanceBins = the group's size
  barrier();
  // A grid of 64 groups walks the frame in strides.
  for (int p = int(gl_GlobalInvocationID.x); p < push.count; p += int(gl_NumWorkGroups.x) * 256) {
    float l = luminance(texels[p].rgb);
    int bin = luminanceBin(l);
    if (bin >= 0) atomicAdd(counts[bin], 1u);
  }
  barrier();
  if (counts[i] != 0u) atomicAdd(bins[i], counts[i]);
}
