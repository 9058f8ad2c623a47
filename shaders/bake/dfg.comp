#version 450
// The DFG table (integrateDfgLut in src/bake/dfg.cpp): one invocation per texel, the same
// points and integrand (ibl/shared/brdf.h).
#extension GL_GOOGLE_include_directive : require
#include "ibl/shared/brdf.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) writeonly buffer Lut { vec4 texels[]; };
layout(push_constant) uniform Params { uint width; uint height; uint samples; } params;

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;
  if (id.x >= params.width || id.y >= params.height) return;
  float NoV = (float(id.x) + 0.5) / float(params.width);
  float roughness = (float(id.y) + 0.5) / float(params.height);
  float alpha = roughness * roughness;
  vec3 v = vec3(sqrt(max(0.0, 1.0 - NoV * NoV)), 0.0, NoV);
  float g1 = smithGgxMasking(NoV, alpha);
  VisibleNormalFrame visibleNormals = visibleNormalFrame(v, alpha);
  vec3 sum = vec3(0.0);
  for (uint k = 0u; k < params.samples; ++k) {
    vec2 xi = hammersley(k, params.samples);
    vec3 h = visibleNormalFromDisk(visibleNormals, uniformDiskPoint(xi));
    sum += dfgIntegrand(v, alpha, roughness, g1, h, sampleCosineHemisphere(xi));
  }
  texels[id.y * params.width + id.x] = vec4(sum / float(params.samples), 1.0);
}
