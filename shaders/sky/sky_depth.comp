#version 450
// The optical-depth table: one texel per invocation (SkyModel::Tables::buildDepth).
layout(local_size_x = 64) in;
#include "sky/atmosphere.glsl"

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= kDepthTableMu * kDepthTableR) return;
  AtmosphereShape a = atmosphereShape();
  vec2 rm = depthTableRadiusAndCosine(a, float(i % kDepthTableMu) / float(kDepthTableMu - 1),
                                      float(i / kDepthTableMu) / float(kDepthTableR - 1));
  depth[i] = vec4(columnDensitiesToTop(a, rm.x, rm.y), 0.0f);
}
