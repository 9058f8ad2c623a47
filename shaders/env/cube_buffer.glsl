// Seam-aware lookups in cube maps held in a storage buffer (src/env/cubemap.cpp's fetchTexelAcrossEdges,
// sampleBilinear and sampleCubic). The including shader declares `texels` (vec4: every level,
// faces, rows, texels) and `levels` (uvec2: size and first texel of each level). Needs
// ibl/shared/cube.h.

vec3 texel(int level, int face, int x, int y) {
  int n = int(levels[level].x);
  return texels[levels[level].y + uint((face * n + y) * n + x)].rgb;
}

// fetchTexelAcrossEdges: past an edge, the extended texel center projected onto the
// neighbouring face, interpolated there.
vec3 fetch(int level, int face, int x, int y) {
  int n = int(levels[level].x);
  if (x >= 0 && y >= 0 && x < n && y < n) return texel(level, face, x, y);
  float inv = 2.0 / float(n);
  FacePoint p = directionToFace(faceToDirection(face, (float(x) + 0.5) * inv - 1.0, (float(y) + 0.5) * inv - 1.0));
  int f = p.face;
  float fx = clamp(p.s * float(n) - 0.5, 0.0, float(n - 1)), fy = clamp(p.t * float(n) - 0.5, 0.0, float(n - 1));
  int x0 = min(int(fx), n - 1), y0 = min(int(fy), n - 1);
  int x1 = min(x0 + 1, n - 1), y1 = min(y0 + 1, n - 1);
  float wx = fx - float(x0), wy = fy - float(y0);
  return mix(mix(texel(level, f, x0, y0), texel(level, f, x1, y0), wx),
             mix(texel(level, f, x0, y1), texel(level, f, x1, y1), wx), wy);
}

// Where a direction falls in a level of size n (texelPosition in src/env/cubemap.cpp): its face, the
// texel whose center is at or before it in x and y, and the fractions past that center.
struct TexelPosition {
  int face;
  ivec2 corner;
  vec2 frac;
};
TexelPosition texelPosition(vec3 dir, int n) {
  FacePoint p = directionToFace(dir);
  vec2 f = vec2(p.s, p.t) * float(n) - 0.5;
  vec2 fl = floor(f);
  return TexelPosition(p.face, ivec2(fl), f - fl);
}

vec3 sampleBilinear(int level, vec3 dir) {
  TexelPosition t = texelPosition(dir, int(levels[level].x));
  int face = t.face, x0 = t.corner.x, y0 = t.corner.y;
  float wx = t.frac.x, wy = t.frac.y;
  return mix(mix(fetch(level, face, x0, y0), fetch(level, face, x0 + 1, y0), wx),
             mix(fetch(level, face, x0, y0 + 1), fetch(level, face, x0 + 1, y0 + 1), wx), wy);
}

// The Catmull-Rom reconstruction from a 4 x 4 window of taps (reconstructFromWindow in
// src/env/cubemap.cpp); `steep` is set when the window is steep.
vec3 reconstructFromWindow(vec3 taps[16], vec2 frac, inout bool steep) {
  vec3 lo = taps[0], hi = taps[0];
  for (int k = 1; k < 16; ++k) {
    lo = min(lo, taps[k]);
    hi = max(hi, taps[k]);
  }
  steep = steep || windowIsSteep(lo, hi);
  vec4 wx = catmullRomWeights(frac.x), wy = catmullRomWeights(frac.y);
  vec3 sum = vec3(0.0);
  for (int j = 0; j < 4; ++j)
    sum += (taps[4 * j] * wx[0] + taps[4 * j + 1] * wx[1] + taps[4 * j + 2] * wx[2] +
            taps[4 * j + 3] * wx[3]) *
           wy[j];
  return sum;
}

// Catmull-Rom reconstruction, 4 x 4 taps across face edges (sampleCubic in src/env/cubemap.cpp).
vec3 sampleCubic(int level, vec3 dir, inout bool steep) {
  TexelPosition t = texelPosition(dir, int(levels[level].x));
  vec3 taps[16];
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      taps[4 * j + i] = fetch(level, t.face, t.corner.x - 1 + i, t.corner.y - 1 + j);
  return reconstructFromWindow(taps, t.frac, steep);
}
