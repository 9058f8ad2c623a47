#version 450
// A halving of the bloom's pyramid: the separable tent (bloomTap) over the 4 x 4 source texels
// around each 2 x 2 block, edges clamped (halve in src/render/bloom.cpp).
#extension GL_GOOGLE_include_directive : require
#include "bloom.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= pass.width || p.y >= pass.height) return;
  vec3 sum = vec3(0.0);
  for (int j = 0; j < 4; ++j) {
    int sy = clamp(2 * p.y - 1 + j, 0, pass.sourceHeight - 1);
    for (int i = 0; i < 4; ++i) {
      int sx = clamp(2 * p.x - 1 + i, 0, pass.sourceWidth - 1);
      sum += (bloomTap(i) * bloomTap(j)) * chainAt(pass.source, pass.sourceWidth, sx, sy);
    }
  }
  texels[pass.target + p.y * pass.width + p.x] = vec4(sum, 0.0);
}
