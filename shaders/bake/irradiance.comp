#version 450
// Irradiance E(n)/pi by direct convolution (convolveIrradiance in src/bake/prefilter.cpp):
// sum L max(0, n.l) omega / sum max(0, n.l) omega over every source texel.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Source { vec4 dirOmega[]; };    // direction, solid angle
layout(std430, binding = 1) readonly buffer Radiance { vec4 radiance[]; };  // rgb
layout(std430, binding = 2) readonly buffer Targets { vec4 normals[]; };    // output texel directions
layout(std430, binding = 3) writeonly buffer Result { vec4 result[]; };
layout(push_constant) uniform Params { uint sourceCount; uint targetCount; } params;

void main() {
  uint t = gl_GlobalInvocationID.x;
  if (t >= params.targetCount) return;
  vec3 n = normals[t].xyz;
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (uint i = 0u; i < params.sourceCount; ++i) {
    vec4 s = dirOmega[i];
    float w = max(dot(n, s.xyz), 0.0) * s.w;
    sum += w * radiance[i].rgb;
    weight += w;
  }
  result[t] = vec4(weight > 0.0 ? sum / weight : vec3(0.0), 1.0);
}
