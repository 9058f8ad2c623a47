#version 450
// One mip level of a cube map (buildMipChain in src/env/cubemap.cpp): each texel is the
// solid-angle weighted mean of its 2 x 2 children (solid angles from the host, as the CPU uses).
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) readonly buffer Parent { vec4 parent[]; };
layout(std430, binding = 1) readonly buffer Omega { float omega[]; };  // parent texel solid angles (one face)
layout(std430, binding = 2) writeonly buffer Child { vec4 child[]; };
layout(push_constant) uniform Params { uint size; } params;  // child size

void main() {
  uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y, face = gl_GlobalInvocationID.z;
  uint n = params.size, np = 2u * n;
  if (x >= n || y >= n) return;
  vec3 sum = vec3(0.0);
  float wsum = 0.0;
  for (uint j = 0u; j < 2u; ++j)
    for (uint i = 0u; i < 2u; ++i) {
      uint cx = 2u * x + i, cy = 2u * y + j;
      float w = omega[cy * np + cx];
      sum += parent[(face * np + cy) * np + cx].rgb * w;
      wsum += w;
    }
  child[(face * n + y) * n + x] = vec4(sum / wsum, 1.0);
}
