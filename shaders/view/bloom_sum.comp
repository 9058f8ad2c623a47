#version 450
// The bloom's renormalization: the per-channel sums over the image of the excess (source) and of
// the spread light (other), width x height texels each. First stage (target >= 0): kBloomGroups
// work groups, each summing a strided share of the texels into its two partials; second stage
// (target < 0, one work group): the partials added, and the scale that makes the spread light's
// total the excess's (0 for a channel with nothing spread) written to texel kBloomScale.
#extension GL_GOOGLE_include_directive : require
#include "bloom.glsl"
layout(local_size_x = 256) in;
shared vec3 excessSums[256];
shared vec3 spreadSums[256];

void main() {
  uint local = gl_LocalInvocationID.x;
  vec3 excess = vec3(0.0), spread = vec3(0.0);
  if (pass.target >= 0) {
    int count = pass.width * pass.height;
    for (int i = int(gl_GlobalInvocationID.x); i < count; i += kBloomGroups * 256) {
      excess += texels[pass.source + i].rgb;
      spread += texels[pass.other + i].rgb;
    }
  } else {
    for (int g = int(local); g < kBloomGroups; g += 256) {
      excess += texels[kBloomPartials + 2 * g].rgb;
      spread += texels[kBloomPartials + 2 * g + 1].rgb;
    }
  }
  excessSums[local] = excess;
  spreadSums[local] = spread;
  barrier();
  for (uint stride = 128u; stride > 0u; stride >>= 1u) {
    if (local < stride) {
      excessSums[local] += excessSums[local + stride];
      spreadSums[local] += spreadSums[local + stride];
    }
    barrier();
  }
  if (local != 0u) return;
  if (pass.target >= 0) {
    texels[kBloomPartials + 2 * int(gl_WorkGroupID.x)] = vec4(excessSums[0], 0.0);
    texels[kBloomPartials + 2 * int(gl_WorkGroupID.x) + 1] = vec4(spreadSums[0], 0.0);
  } else {
    vec3 total = excessSums[0], spreadTotal = spreadSums[0], scale = vec3(0.0);
    for (int c = 0; c < 3; ++c)
      if (spreadTotal[c] > 0.0) scale[c] = total[c] / spreadTotal[c];
    texels[kBloomScale] = vec4(scale, 0.0);
  }
}
