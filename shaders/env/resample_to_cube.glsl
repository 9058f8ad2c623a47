// Equirect or cube -> cube (resampleToCube in src/env/resample.cpp): each texel integrates the
// cubic B-spline reconstruction of the (reduced) source, a panorama or one cube level, with
// k x k samples weighted by the exact sub-cell solid angles the host computed. Included by
// equirect_to_cube.comp and cube_to_cube.comp, which define CUBE_SOURCE 0 or 1. Needs
// ibl/shared/cube.h.
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) readonly buffer Source { vec4 texels[]; };  // panorama or cube level
layout(std430, binding = 1) readonly buffer Levels { uvec2 levels[]; };  // cube: (size, 0)
layout(std430, binding = 2) readonly buffer Weights { float weights[]; };
layout(std430, binding = 3) writeonly buffer Result { vec4 result[]; };
layout(push_constant) uniform Params {
  uint size, k, width, height;  // width, height: of the panorama
  vec4 toSource[3];  // columns of the inverse rotation about +Y (rotationY in src/env/resample.cpp)
} params;
#include "env/cube_buffer.glsl"

// sampleEquirectCubic in src/env/equirect.cpp: wraps in u, clamps at the poles.
vec3 sampleEquirectCubic(float u, float v) {
  int w = int(params.width), h = int(params.height);
  float fx = u * float(w) - 0.5, fy = v * float(h) - 0.5;
  float flx = floor(fx), fly = floor(fy);
  vec4 wx = cubicBSplineWeights(fx - flx), wy = cubicBSplineWeights(fy - fly);
  int x0 = int(flx) - 1, y0 = int(fly) - 1;
  vec3 sum = vec3(0.0);
  for (int j = 0; j < 4; ++j) {
    int y = clamp(y0 + j, 0, h - 1);
    vec3 row = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
      int x = (x0 + i) % w;
      if (x < 0) x += w;
      row += texels[y * w + x].rgb * wx[i];
    }
    sum += row * wy[j];
  }
  return sum;
}

vec3 sampleSource(vec3 d) {
#if CUBE_SOURCE
  return sampleCubic(0, d);
#else
  // directionToEquirect: u = 0.5 + atan2(z, x) / 2 pi, v = atan2(sqrt(x^2 + z^2), y) / pi.
  float u = 0.5 + atan(d.z, d.x) / (2.0 * kPi);
  float v = atan(sqrt(d.x * d.x + d.z * d.z), d.y) / kPi;
  return sampleEquirectCubic(u, v);
#endif
}

void main() {
  uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y, face = gl_GlobalInvocationID.z;
  uint n = params.size, k = params.k, sub = n * k;
  if (x >= n || y >= n) return;
  float inv = 2.0 / float(sub);
  vec3 sum = vec3(0.0);
  float wsum = 0.0;
  for (uint b = 0u; b < k; ++b) {
    uint j = y * k + b;
    float tc = (float(j) + 0.5) * inv - 1.0;
    for (uint a = 0u; a < k; ++a) {
      uint i = x * k + a;
      float sc = (float(i) + 0.5) * inv - 1.0;
      vec3 d = mat3(params.toSource[0].xyz, params.toSource[1].xyz, params.toSource[2].xyz) *
               faceToDirection(int(face), sc, tc);
      float w = weights[j * sub + i];
      sum += sampleSource(d) * w;
      wsum += w;
    }
  }
  result[(face * n + y) * n + x] = vec4(sum / wsum, 1.0);
}
