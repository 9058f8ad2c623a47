// Equirect or cube -> cube (resampleToCube in src/env/resample.cpp): each texel integrates the
// Catmull-Rom reconstruction of the (reduced) source, a panorama or one cube level, with k x k
// samples weighted by the exact sub-cell solid angles the host computed, and again with
// k2 x k2 where a sample's window is steep. Included by equirect_to_cube.comp and
// cube_to_cube.comp, which define CUBE_SOURCE 0 or 1. Needs ibl/shared/cube.h.
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) readonly buffer Source { vec4 texels[]; };  // panorama or cube level
layout(std430, binding = 1) readonly buffer Levels { uvec2 levels[]; };  // cube: (size, 0)
// The (size k)^2 sub-cell solid angles of a face, then the (size k2)^2.
layout(std430, binding = 2) readonly buffer Weights { float weights[]; };
layout(std430, binding = 3) writeonly buffer Result { vec4 result[]; };
layout(push_constant) uniform Params {
  uint size, k, width, height;  // width, height: of the panorama
  uint k2, pad0, pad1, pad2;    // samples per side where a window is steep
  vec4 toSource[3];  // columns of the inverse rotation about +Y (rotationY in src/env/resample.cpp)
} params;
#include "env/cube_buffer.glsl"

// sampleEquirectCubic in src/env/equirect.cpp: wraps in u, clamps at the poles.
vec3 sampleEquirectCubic(float u, float v, inout bool steep) {
  int w = int(params.width), h = int(params.height);
  float fx = u * float(w) - 0.5, fy = v * float(h) - 0.5;
  float flx = floor(fx), fly = floor(fy);
  int x0 = int(flx) - 1, y0 = int(fly) - 1;
  vec3 taps[16];
  for (int j = 0; j < 4; ++j) {
    int y = clamp(y0 + j, 0, h - 1);
    for (int i = 0; i < 4; ++i) {
      int x = (x0 + i) % w;
      if (x < 0) x += w;
      taps[4 * j + i] = texels[y * w + x].rgb;
    }
  }
  return reconstructFromWindow(taps, vec2(fx - flx, fy - fly), steep);
}

vec3 sampleSource(vec3 d, inout bool steep) {
#if CUBE_SOURCE
  return sampleCubic(0, d, steep);
#else
  // directionToEquirect: u = 0.5 + atan2(z, x) / 2 pi, v = atan2(sqrt(x^2 + z^2), y) / pi.
  float u = 0.5 + atan(d.z, d.x) / (2.0 * kPi);
  float v = atan(sqrt(d.x * d.x + d.z * d.z), d.y) / kPi;
  return sampleEquirectCubic(u, v, steep);
#endif
}

// The weighted mean of n x n samples over texel (x, y) of `face`; the sub-cell solid angles
// start at weights[offset].
vec3 integrateTexel(uint face, uint x, uint y, uint n, uint offset, inout bool steep) {
  uint sub = params.size * n;
  float inv = 2.0 / float(sub);
  mat3 toSource = mat3(params.toSource[0].xyz, params.toSource[1].xyz, params.toSource[2].xyz);
  vec3 sum = vec3(0.0);
  float wsum = 0.0;
  for (uint b = 0u; b < n; ++b) {
    uint j = y * n + b;
    float tc = (float(j) + 0.5) * inv - 1.0;
    for (uint a = 0u; a < n; ++a) {
      uint i = x * n + a;
      float sc = (float(i) + 0.5) * inv - 1.0;
      float w = weights[offset + j * sub + i];
      sum += sampleSource(toSource * faceToDirection(int(face), sc, tc), steep) * w;
      wsum += w;
    }
  }
  return sum / wsum;
}

void main() {
  uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y, face = gl_GlobalInvocationID.z;
  uint n = params.size, k = params.k;
  if (x >= n || y >= n) return;
  bool steep = false;
  vec3 value = integrateTexel(face, x, y, k, 0u, steep);
  if (steep && params.k2 > k) {
    bool unused = false;
    value = integrateTexel(face, x, y, params.k2, n * k * n * k, unused);
  }
  // w: whether the texel is steep, for unsharpAreaBlur on the host.
  result[(face * n + y) * n + x] = vec4(value, steep ? 1.0 : 0.0);
}
