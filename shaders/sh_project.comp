#version 450
// SH9 projection (projectSh9 in src/sh.cpp): each workgroup sums L Y_lm omega over 64 texels
// in shared memory and writes one partial sum per coefficient; the host adds the partials in
// a fixed order.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Source { vec4 dirOmega[]; };
layout(std430, binding = 1) readonly buffer Radiance { vec4 radiance[]; };
layout(std430, binding = 2) writeonly buffer Partials { vec4 partials[]; };  // 9 per workgroup
layout(push_constant) uniform Params { uint sourceCount; } params;
shared vec3 sums[64][9];

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint local = gl_LocalInvocationID.x;
  float basis[9];
  vec3 l = vec3(0.0);
  if (i < params.sourceCount) {
    vec3 d = dirOmega[i].xyz;
    l = radiance[i].rgb * dirOmega[i].w;
    basis = float[9](0.282095, 0.488603 * d.y, 0.488603 * d.z, 0.488603 * d.x, 1.092548 * d.x * d.y,
                     1.092548 * d.y * d.z, 0.315392 * (3.0 * d.z * d.z - 1.0), 1.092548 * d.x * d.z,
                     0.546274 * (d.x * d.x - d.y * d.y));
  } else {
    basis = float[9](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
  }
  for (int k = 0; k < 9; ++k) sums[local][k] = l * basis[k];
  barrier();
  for (uint stride = 32u; stride > 0u; stride >>= 1u) {
    if (local < stride)
      for (int k = 0; k < 9; ++k) sums[local][k] += sums[local + stride][k];
    barrier();
  }
  if (local == 0u)
    for (int k = 0; k < 9; ++k) partials[gl_WorkGroupID.x * 9u + uint(k)] = vec4(sums[0][k], 0.0);
}
