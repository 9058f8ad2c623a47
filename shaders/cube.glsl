const float kPiCube = 3.14159265358979;

// Cube maps in storage buffers (faces +X..-Z, rows, texels; levels one after another), with
// the face table and seam-aware bilinear / trilinear lookups of src/cubemap.cpp.

vec3 faceToDirection(int face, float sc, float tc) {
  if (face == 0) return vec3(1.0, -tc, -sc);
  if (face == 1) return vec3(-1.0, -tc, sc);
  if (face == 2) return vec3(sc, 1.0, tc);
  if (face == 3) return vec3(sc, -1.0, -tc);
  if (face == 4) return vec3(sc, -tc, 1.0);
  return vec3(-sc, -tc, -1.0);
}

// (face, s, t) of a direction; s, t in [0, 1].
vec3 directionToFace(vec3 d) {
  vec3 a = abs(d);
  float face, ma, sc, tc;
  if (a.x >= a.y && a.x >= a.z) {
    face = d.x >= 0.0 ? 0.0 : 1.0;
    ma = a.x;
    sc = d.x >= 0.0 ? -d.z : d.z;
    tc = -d.y;
  } else if (a.y >= a.z) {
    face = d.y >= 0.0 ? 2.0 : 3.0;
    ma = a.y;
    sc = d.x;
    tc = d.y >= 0.0 ? d.z : -d.z;
  } else {
    face = d.z >= 0.0 ? 4.0 : 5.0;
    ma = a.z;
    sc = d.z >= 0.0 ? d.x : -d.x;
    tc = -d.y;
  }
  if (!(ma > 0.0)) return vec3(4.0, 0.5, 0.5);
  return vec3(face, 0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0));
}

vec3 texelDirection(int face, int x, int y, int n) {
  float inv = 2.0 / float(n);
  return normalize(faceToDirection(face, (float(x) + 0.5) * inv - 1.0, (float(y) + 0.5) * inv - 1.0));
}

// Duff et al. 2017 (tangentFrame in sampling.cpp).
mat3 tangentFrame(vec3 n) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float b = n.x * n.y * a;
  return mat3(vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x), vec3(b, s + n.y * n.y * a, -n.y), n);
}

// Face axes of the face table: major axis, direction of growing s, of growing t (kFaceAxes in
// src/prefilter.cpp).
vec3 faceAxis(int face, int which) {
  const vec3 axes[18] = vec3[18](
      vec3(1, 0, 0), vec3(0, 0, -1), vec3(0, -1, 0), vec3(-1, 0, 0), vec3(0, 0, 1), vec3(0, -1, 0),
      vec3(0, 1, 0), vec3(1, 0, 0), vec3(0, 0, 1), vec3(0, -1, 0), vec3(1, 0, 0), vec3(0, 0, -1),
      vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, -1, 0), vec3(0, 0, -1), vec3(-1, 0, 0), vec3(0, -1, 0));
  return axes[face * 3 + which];
}

// Cubic B-spline weights of the 4 taps around a sample at fraction t (cubicBSplineWeights in
// cubemap.hpp).
vec4 cubicBSplineWeights(float t) {
  float t2 = t * t, t3 = t2 * t, s = 1.0 - t;
  return vec4(s * s * s, 3.0 * t3 - 6.0 * t2 + 4.0, -3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0, t3) / 6.0;
}
