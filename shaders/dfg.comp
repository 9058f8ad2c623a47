#version 450
// The DFG table (integrateDfgLut in src/dfg.cpp): one invocation per texel.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
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
  float a2 = alpha * alpha;
  float g1 = 2.0 * NoV / (NoV + sqrt(a2 + (1.0 - a2) * NoV * NoV));
  float a = 0.0, b = 0.0, d = 0.0;
  for (uint k = 0u; k < params.samples; ++k) {
    vec2 xi = hammersley(k, params.samples);
    vec3 h = sampleGgxVisibleNormal(v, uniformDiskPoint(xi), alpha);
    float VoH = dot(v, h);
    float NoL = 2.0 * VoH * h.z - v.z;
    if (NoL > 0.0 && VoH > 0.0) {
      float g = 4.0 * smithGgxCorrelatedVisibility(NoV, NoL, alpha) * NoL * NoV / g1;
      float fc = schlickWeight(VoH);
      a += (1.0 - fc) * g;
      b += fc * g;
    }
    vec3 l = sampleCosineHemisphere(xi);
    vec3 hd = normalize(v + l);
    d += disneyDiffuseRenormalized(NoV, l.z, dot(l, hd), roughness);
  }
  texels[id.y * params.width + id.x] = vec4(vec3(a, b, d) / float(params.samples), 1.0);
}
