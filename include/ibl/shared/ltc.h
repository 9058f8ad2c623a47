// API: internal (may change without notice; math shared with the shaders)
// Linearly transformed cosines (Heitz, Dupuy, Hill & Neubelt 2016, "Real-Time Polygonal-Light
// Shading with Linearly Transformed Cosines"): the GGX lobe times the cosine, for a given
// roughness and view, is approximated by a clamped cosine distribution D_o transformed by a
// 3 x 3 matrix M; the integral of the lobe over a polygon is then the integral of D_o over the
// polygon transformed by M^-1, which has a closed form (Lambert's, through the vector form
// factor). C++ and GLSL (see lang.h): the real-time area lights (lights.h) and the table's
// fitter (src/render/ltc.cpp) use the same definitions.
//
// A table entry holds M^-1 in the frame of the shaded point, x toward the tangential part of the
// view, z along the normal (the lobe is symmetric about the xz plane), scaled so that its middle
// entry is 1 (a scale of M^-1 changes neither the distribution nor the polygon's integral):
//   M^-1 = [[c.x, 0, c.y], [0, 1, 0], [c.z, 0, c.w]].
#ifndef IBL_SHARED_LTC_H
#define IBL_SHARED_LTC_H
#include "ibl/shared/lang.h"

IBL_BEGIN

// Where the table of entries is read for a perceptual roughness and n.v, in texels of a table
// `size` texels square (texel (i, j) at (i, j), clamped to the edge texels): its columns run over
// the roughness, its rows over sqrt(1 - n.v) (denser toward grazing views, where the lobe
// changes fastest). Both languages interpolate the four texels around it bilinearly with exact
// weights (a GPU sampler's weights may carry as few as 8 bits, and the sharp lobes of smooth
// surfaces magnify the difference).
IBL_FN vec2 ltcTablePosition(float roughness, float NoV, float size) {
  vec2 t = vec2(clamp(roughness, 0.0f, 1.0f), sqrt(clamp(1.0f - NoV, 0.0f, 1.0f)));
  return t * (size - 1.0f);
}

// M^-1 w for the table entry c (w in the shaded point's frame).
IBL_FN vec3 ltcInverseTransform(vec4 c, vec3 w) {
  return vec3(c.x * w.x + c.y * w.z, w.y, c.z * w.x + c.w * w.z);
}

// The LTC's density at unit w: D_o(M^-1 w / |M^-1 w|) |det M^-1| / |M^-1 w|^3, with
// D_o = max(z, 0) / pi (Heitz et al. 2016, eq. 1).
IBL_FN float ltcDensity(vec4 c, vec3 w) {
  vec3 o = ltcInverseTransform(c, w);
  float len2 = dot(o, o);
  float det = abs(c.x * c.w - c.y * c.z);
  return max(o.z, 0.0f) / kPi * det / (len2 * len2);
}

// The frame of the LTC table at a shaded point: x the tangential part of the view, z = n.
struct LtcFrame {
  vec3 t1, t2, n;
  vec4 c;  // the table entry; vec4(1, 0, 0, 1): the cosine itself (Lambert)
};
IBL_FN LtcFrame ltcFrame(vec3 n, vec3 v, vec4 c) {
  LtcFrame f;
  vec3 t = v - n * dot(n, v);
  float len = length(t);
  // Seen along the normal the lobe is round, and any tangent will do.
  f.t1 = len > 1e-6f ? t / len
                     : normalize(abs(n.x) < 0.9f ? cross(n, vec3(1.0f, 0.0f, 0.0f))
                                                 : cross(n, vec3(0.0f, 1.0f, 0.0f)));
  f.t2 = cross(n, f.t1);
  f.n = n;
  f.c = c;
  return f;
}
// A point relative to the shaded point, taken into the space of the untransformed cosine.
IBL_FN vec3 ltcToCosineSpace(LtcFrame f, vec3 p) {
  return ltcInverseTransform(f.c, vec3(dot(p, f.t1), dot(p, f.t2), dot(p, f.n)));
}
// A vector of the cosine space (such as a form factor vector) back in world space, through the
// frame only (for a direction to evaluate a diffuse lobe toward, with the identity entry).
IBL_FN vec3 ltcFrameToWorld(LtcFrame f, vec3 w) {
  return w.x * f.t1 + w.y * f.t2 + w.z * f.n;
}

// One edge's term of the vector form factor (Arvo 1995, "Applications of Irradiance Tensors",
// eq. 8; Lambert): the arc's angle times the unit normal of the plane through the edge and the
// origin. a, b: unit directions of the edge's ends.
// The angle from atan2(sin, cos): acos loses half the digits of short edges (far lights).
IBL_FN vec3 edgeFormFactorVector(vec3 a, vec3 b) {
  vec3 c = cross(a, b);
  float s = length(c);
  float theta = atan(s, dot(a, b));
  return s > 1e-12f ? c * (theta / s) : c;
}

// The integral of the clamped cosine over a convex polygon, its edges given one at a time (no
// arrays: the same text is GLSL), clipped to the upper hemisphere on the way: an edge that leaves
// it ends at the horizon, one that enters starts there, and the arc along the horizon between
// the exit and the entry closes the clipped polygon (a convex polygon crosses a plane at most
// twice).
struct HorizonClippedPolygon {
  vec3 sum;
  vec3 exitPoint, entryPoint;
  bool exited, entered;
};
IBL_FN HorizonClippedPolygon horizonClippedPolygon() {
  HorizonClippedPolygon h;
  h.sum = vec3(0.0f);
  h.exitPoint = vec3(0.0f);
  h.entryPoint = vec3(0.0f);
  h.exited = false;
  h.entered = false;
  return h;
}
// The edge a -> b, unit directions in cosine space. Where the edge crosses the horizon, the
// straight chord between the unit points and the arc between them cross it at the same
// direction (both lie in the plane through a, b and the origin).
IBL_FN HorizonClippedPolygon addPolygonEdge(HorizonClippedPolygon h, vec3 a, vec3 b) {
  bool aUp = a.z > 0.0f, bUp = b.z > 0.0f;
  if (aUp && bUp) {
    h.sum += edgeFormFactorVector(a, b);
  } else if (aUp || bUp) {
    vec3 x = mix(a, b, a.z / (a.z - b.z));
    x.z = 0.0f;
    x = normalize(x);
    if (aUp) {
      h.sum += edgeFormFactorVector(a, x);
      h.exitPoint = x;
      h.exited = true;
    } else {
      h.sum += edgeFormFactorVector(x, b);
      h.entryPoint = x;
      h.entered = true;
    }
  }
  return h;
}

// The vector form factor of the clipped polygon, oriented upward: its z is the integral of
// D_o = cos / pi over the polygon (the form factor), its direction the polygon's mean direction.
IBL_FN vec3 polygonFormFactorVector(HorizonClippedPolygon h) {
  vec3 s = h.sum;
  if (h.exited && h.entered) s += edgeFormFactorVector(h.exitPoint, h.entryPoint);
  s *= 0.5f / kPi;
  return s.z < 0.0f ? -s : s;
}

// The LTC's integral over the quadrilateral p0 p1 p2 p3 (relative to the shaded point, in order
// around it): its vector form factor in cosine space.
IBL_FN vec3 ltcQuadIntegral(LtcFrame f, vec3 p0, vec3 p1, vec3 p2, vec3 p3) {
  vec3 q0 = normalize(ltcToCosineSpace(f, p0)), q1 = normalize(ltcToCosineSpace(f, p1));
  vec3 q2 = normalize(ltcToCosineSpace(f, p2)), q3 = normalize(ltcToCosineSpace(f, p3));
  HorizonClippedPolygon h = horizonClippedPolygon();
  h = addPolygonEdge(h, q0, q1);
  h = addPolygonEdge(h, q1, q2);
  h = addPolygonEdge(h, q2, q3);
  h = addPolygonEdge(h, q3, q0);
  return polygonFormFactorVector(h);
}

// A disk as the regular polygon of kLtcDiskSides sides with the same area (its circumradius
// scaled by sqrt(2 pi / (k sin(2 pi / k)))): the disk's integral within the polygon's shape
// error (measured in tests/shared/test_lights_ltc.cpp).
const int kLtcDiskSides = 16;
const float kLtcDiskRadiusScale = 1.0130016f;  // sqrt(2 pi / (16 sin(pi / 8)))
const float kLtcDiskCosStep = 0.92387953f;     // cos(2 pi / 16)
const float kLtcDiskSinStep = 0.38268343f;     // sin(2 pi / 16)

// The LTC's integral over the disk of center c (relative to the shaded point), unit axes u and w
// spanning its plane, and radius.
IBL_FN vec3 ltcDiskIntegral(LtcFrame f, vec3 c, vec3 u, vec3 w, float radius) {
  float r = radius * kLtcDiskRadiusScale;
  vec3 cu = ltcToCosineSpace(f, c), uu = ltcToCosineSpace(f, u * r),
       wu = ltcToCosineSpace(f, w * r);
  float cs = 1.0f, sn = 0.0f;
  vec3 first = normalize(cu + uu);
  vec3 previous = first;
  HorizonClippedPolygon h = horizonClippedPolygon();
  for (int i = 1; i < kLtcDiskSides; ++i) {
    float next = cs * kLtcDiskCosStep - sn * kLtcDiskSinStep;
    sn = sn * kLtcDiskCosStep + cs * kLtcDiskSinStep;
    cs = next;
    vec3 current = normalize(cu + cs * uu + sn * wu);
    h = addPolygonEdge(h, previous, current);
    previous = current;
  }
  h = addPolygonEdge(h, previous, first);
  return polygonFormFactorVector(h);
}

IBL_END

#endif
