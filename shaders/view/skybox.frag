#version 450
// The background: the source cube seen along each pixel's ray (at a chosen mip level), or a
// flat color, and the emitters seen against it. Alpha 0: no model there.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "view/frame.glsl"
#include "view/shading.glsl"
layout(location = 0) out vec4 outColor;

void main() {
  if (frame.bufferView.x != 0) {  // a buffer view: no surface, black
    outColor = vec4(0.0);
    return;
  }
  Ray r = primaryRay(gl_FragCoord.xy);
  vec3 color = frame.background.w > 0.5 ? textureLod(sourceMap, r.direction, frame.lods.z).rgb
                                        : frame.background.rgb;
  float alpha = 0.0;
  // The scene's area lights and the sun in front of the background (an area light covers the
  // pixel as a surface does; the sun does not).
  vec3 emitted;
  bool surface;
  if (nearestEmitter(r, gl_FragCoord.xy, 3.0e38, emitted, surface)) {
    color = emitted;
    alpha = surface ? 1.0 : 0.0;
  }
  outColor = vec4(color, alpha);
}
