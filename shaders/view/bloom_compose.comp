#version 450
// The bloom's last pass: the frame (source) less its excess (other) plus the spread light
// (target) times the renormalization's scale, written over the spread light; width x height.
#extension GL_GOOGLE_include_directive : require
#include "bloom.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= pass.width || p.y >= pass.height) return;
  int i = p.y * pass.width + p.x;
  vec3 scale = texels[kBloomScale].rgb;
  vec3 c = texels[pass.source + i].rgb - texels[pass.other + i].rgb + texels[pass.target + i].rgb * scale;
  texels[pass.target + i] = vec4(c, 1.0);
}
