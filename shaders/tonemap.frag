#version 450
// The window's last pass: exposure and tone curve (toneMap in src/camera.cpp), then sRGB
// encoding unless the swapchain's format encodes.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(push_constant) uniform Params {
  float exposure;
  int curve;   // 0 none, 1 ACES, 2 filmic
  int encode;  // 1: write sRGB-encoded values
} params;
layout(location = 0) out vec4 outColor;

vec3 hable(vec3 x) {
  const float a = 0.15, b = 0.50, c = 0.10, d = 0.20, e = 0.02, f = 0.30;
  return (x * (a * x + c * b) + d * e) / (x * (a * x + b) + d * f) - e / f;
}

vec3 toneMap(vec3 c, int curve) {
  if (curve == 1) return clamp((c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0);
  if (curve == 2) return clamp(hable(c * 2.0) / hable(vec3(11.2)), 0.0, 1.0);
  return clamp(c, 0.0, 1.0);
}

void main() {
  vec3 c = toneMap(texelFetch(hdr, ivec2(gl_FragCoord.xy), 0).rgb * params.exposure, params.curve);
  if (params.encode != 0) c = vec3(linearToSrgb(c.r), linearToSrgb(c.g), linearToSrgb(c.b));
  outColor = vec4(c, 1.0);
}
