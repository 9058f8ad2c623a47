#version 450
// A doubling of the bloom's pyramid: the source brought bilinearly to the target's size (about
// twice its own), edges clamped, plus the level `other` at the same size (-1: nothing; it may be
// the target itself, each texel read before it is written) (doubleOnto in src/render/bloom.cpp).
#extension GL_GOOGLE_include_directive : require
#include "bloom.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= pass.width || p.y >= pass.height) return;
  float sy = bloomDoublingCoordinate(p.y, pass.sourceHeight);
  int y0 = int(sy), y1 = min(y0 + 1, pass.sourceHeight - 1);
  float fy = sy - float(y0);
  float sx = bloomDoublingCoordinate(p.x, pass.sourceWidth);
  int x0 = int(sx), x1 = min(x0 + 1, pass.sourceWidth - 1);
  float fx = sx - float(x0);
  vec3 top = mix(chainAt(pass.source, pass.sourceWidth, x0, y0),
                 chainAt(pass.source, pass.sourceWidth, x1, y0), fx);
  vec3 bottom = mix(chainAt(pass.source, pass.sourceWidth, x0, y1),
                    chainAt(pass.source, pass.sourceWidth, x1, y1), fx);
  int i = p.y * pass.width + p.x;
  vec3 base = pass.other >= 0 ? texels[pass.other + i].rgb : vec3(0.0);
  texels[pass.target + i] = vec4(mix(top, bottom, fy) + base, 0.0);
}
