// API: internal (may change without notice; math shared with the shaders)
// Cube-map geometry: the face table of the Vulkan / OpenGL specification ("Cube Map Face
// Selection"), faces +X, -X, +Y, -Y, +Z, -Z, and the Catmull-Rom weights of the
// reconstruction filter. C++ and GLSL (see lang.h).
#ifndef IBL_SHARED_CUBE_H
#define IBL_SHARED_CUBE_H
#include "ibl/shared/lang.h"

IBL_BEGIN

// The face table (Vulkan specification, "Cube Map Face Selection"), once: the unnormalized
// direction through the point (sc, tc) in [-1, 1]^2 of a face plane.
//   +X: sc = -z, tc = -y   -X: sc = +z, tc = -y   +Y: sc = +x, tc = +z
//   -Y: sc = +x, tc = -z   +Z: sc = +x, tc = -y   -Z: sc = -x, tc = -y
IBL_FN vec3 faceToDirection(int face, float sc, float tc) {
  if (face == 0) return vec3(1.0f, -tc, -sc);
  if (face == 1) return vec3(-1.0f, -tc, sc);
  if (face == 2) return vec3(sc, 1.0f, tc);
  if (face == 3) return vec3(sc, -1.0f, -tc);
  if (face == 4) return vec3(sc, -tc, 1.0f);
  return vec3(-sc, -tc, -1.0f);
}

// The direction of equirect coordinates (u, v) (docs/conventions.md: u = 0.5 + atan2(z, x) / 2 pi,
// v = acos(y) / pi; row 0 straight up, the image's center toward +X).
IBL_FN vec3 equirectToDirection(float u, float v) {
  float phi = 2.0f * kPi * (u - 0.5f);
  float theta = kPi * v;
  float st = sin(theta);
  return vec3(st * cos(phi), cos(theta), st * sin(phi));
}

// The face's axes, read off the table: which = 0 the major axis (the face center), 1 the
// direction in which s grows, 2 the direction in which t grows; a point of the face plane is
// axis + sc * sAxis + tc * tAxis.
IBL_FN vec3 faceAxis(int face, int which) {
  vec3 center = faceToDirection(face, 0.0f, 0.0f);
  if (which == 0) return center;
  if (which == 1) return faceToDirection(face, 1.0f, 0.0f) - center;
  return faceToDirection(face, 0.0f, 1.0f) - center;
}

// Unit direction through the center of texel (x, y) of a face of n x n texels.
IBL_FN vec3 texelDirection(int face, int x, int y, int n) {
  float inv = 2.0f / float(n);
  return normalize(
      faceToDirection(face, (float(x) + 0.5f) * inv - 1.0f, (float(y) + 0.5f) * inv - 1.0f));
}

// The face a direction hits and its coordinates s, t in [0, 1]: the table read backwards,
// s = (sc / |ma| + 1) / 2, t = (tc / |ma| + 1) / 2 with ma the major axis.
struct FacePoint {
  int face;
  float s;
  float t;
};
IBL_FN FacePoint directionToFace(vec3 d) {
  float ax = abs(d.x), ay = abs(d.y), az = abs(d.z);
  FacePoint p;
  float ma, sc, tc;
  if (ax >= ay && ax >= az) {
    p.face = d.x >= 0.0f ? 0 : 1;
    ma = ax;
    sc = d.x >= 0.0f ? -d.z : d.z;
    tc = -d.y;
  } else if (ay >= az) {
    p.face = d.y >= 0.0f ? 2 : 3;
    ma = ay;
    sc = d.x;
    tc = d.y >= 0.0f ? d.z : -d.z;
  } else {
    p.face = d.z >= 0.0f ? 4 : 5;
    ma = az;
    sc = d.z >= 0.0f ? d.x : -d.x;
    tc = -d.y;
  }
  if (!(ma > 0.0f)) {  // zero or NaN direction: any defined answer
    p.face = 4;
    ma = 1.0f;
    sc = 0.0f;
    tc = 0.0f;
  }
  p.s = 0.5f * (sc / ma + 1.0f);
  p.t = 0.5f * (tc / ma + 1.0f);
  return p;
}

// Weights of the Catmull-Rom spline (the interpolating cubic convolution kernel with a = -1/2,
// Keys 1981, eq. 15) for the taps at -1, 0, 1, 2 around a sample a fraction t past tap 0. They
// sum to 1 and reproduce the taps exactly at t = 0 and 1; the outer weights are negative, so a
// reconstruction may overshoot next to an edge (clamp it to the inner taps' range).
IBL_FN vec4 catmullRomWeights(float t) {
  float t2 = t * t, t3 = t2 * t;
  return vec4(-t3 + 2.0f * t2 - t, 3.0f * t3 - 5.0f * t2 + 2.0f, -3.0f * t3 + 4.0f * t2 + t,
              t3 - t2) *
         0.5f;
}

// Whether a 4 x 4 window of taps, whose per-channel minimum and maximum are lo and hi, is
// steep (a sun, a lamp's edge): its values differ by more than a factor of 16. There the
// Catmull-Rom reconstruction varies fast, and an area integral of it needs finer samples.
IBL_FN bool windowIsSteep(vec3 lo, vec3 hi) {
  return hi.x > 16.0f * lo.x || hi.y > 16.0f * lo.y || hi.z > 16.0f * lo.z;
}

IBL_END

#endif
