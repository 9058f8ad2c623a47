#version 450
// The background: the source cube seen along each pixel's ray (at a chosen mip level), or a
// flat color. Alpha 0: no model there.
#extension GL_GOOGLE_include_directive : require
#include "view/frame.glsl"
layout(location = 0) out vec4 outColor;

void main() {
  vec3 color = frame.background.w > 0.5
                   ? textureLod(sourceMap, primaryRay(gl_FragCoord.xy).direction, frame.lods.z).rgb
                   : frame.background.rgb;
  outColor = vec4(color, 0.0);
}
