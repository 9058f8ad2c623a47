#version 450
// The window's last pass: exposure and tone curve (toneMap of ibl/shared/color.h, as the CPU), then sRGB
// encoding unless the swapchain's format encodes.
#extension GL_GOOGLE_include_directive : require
#include "ibl/shared/color.h"
layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(push_constant) uniform Params {
  float exposure;
  int curve;   // 0 none, 1 ACES, 2 filmic
  int encode;  // 1: write sRGB-encoded values
} params;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 c = toneMap(texelFetch(hdr, ivec2(gl_FragCoord.xy), 0).rgb * params.exposure, params.curve);
  if (params.encode != 0) c = vec3(linearToSrgb(c.r), linearToSrgb(c.g), linearToSrgb(c.b));
  outColor = vec4(c, 1.0);
}
