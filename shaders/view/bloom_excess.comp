#version 450
// The bloom's first pass: each pixel's light above the threshold (bloomExcess), none where the
// frame is not finite, non-negative radiance (left as it is). source: the frame, target: the
// excess, width x height both.
#extension GL_GOOGLE_include_directive : require
#include "bloom.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= pass.width || p.y >= pass.height) return;
  vec3 c = chainAt(pass.source, pass.width, p.x, p.y);
  // Finite and non-negative (false for NaN, whose comparisons all fail).
  bool radiance = all(greaterThanEqual(c, vec3(0.0))) && all(lessThanEqual(c, vec3(3.4028235e38)));
  texels[pass.target + p.y * pass.width + p.x] =
      vec4(radiance ? bloomExcess(c, pass.threshold) : vec3(0.0), 0.0);
}
