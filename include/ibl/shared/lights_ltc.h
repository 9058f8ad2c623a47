// API: internal (may change without notice; math shared with the shaders)
// The area lights (spheres, disks, tubes, rects) through linearly transformed cosines (ltc.h;
// Heitz, Dupuy, Hill & Neubelt 2016): each light's integral over the diffuse and the GGX lobe as
// the incidence it delivers to a point. C++ and GLSL (see lang.h).
#ifndef IBL_SHARED_LIGHTS_LTC_H
#define IBL_SHARED_LIGHTS_LTC_H
#include "ibl/shared/lang.h"
#include "ibl/shared/light_record.h"
#include "ibl/shared/light_units.h"
#include "ibl/shared/lights_frostbite.h"
#include "ibl/shared/ltc.h"
#include "ibl/shared/sampling.h"

IBL_BEGIN

// --- Area lights through linearly transformed cosines (ltc.h; Heitz et al. 2016) ---

// The incidence of an area light from its two integrals: the diffuse lobe's (the cosine itself:
// the exact form factor vector, in the frame of `diffuse`) and the GGX lobe's (the fraction of
// the normalized lobe over the light), each per unit luminance, times the distance window.
IBL_FN LightIncidence ltcIncidence(LtcFrame diffuse, vec3 formFactor, float lobeFraction,
                                   float window) {
  float len = length(formFactor);
  LightIncidence inc =
      noIncidence(len > 0.0f ? ltcFrameToWorld(diffuse, formFactor / len) : diffuse.n);
  inc.diffuseIlluminance = kPi * formFactor.z * window;
  inc.specularLobeFraction = lobeFraction * window;
  return inc;
}

// A sphere of radius r at c covers the same directions as the disk facing the point, at c,
// of radius d tan(sigma) (sin sigma = r / d): the disk's LTC integral is the sphere's.
IBL_FN float sphereAsFacingDiskRadius(vec3 c, float radius) {
  float sinSigmaSqr = min(radius * radius / dot(c, c), 0.9999f);
  return length(c) * sqrt(sinSigmaSqr / (1.0f - sinSigmaSqr));
}
IBL_FN vec3 ltcSphereIntegral(LtcFrame f, vec3 c, float radius) {
  mat3 t = tangentFrame(normalize(c));
  return ltcDiskIntegral(f, c, t[0], t[1], sphereAsFacingDiskRadius(c, radius));
}

// The tube (a capsule: the segment c +- halfLength axis, radius r) as the polygon of its
// silhouette, integrated by the LTC's clipped polygon (Heitz et al. 2016's polygon integral). The
// capsule is the convex hull of its two end spheres, so the cone it subtends is the convex hull
// of theirs: two sides along the cylinder's silhouette lines (the tangent planes through the
// shaded point that contain the axis touch both spheres at p +- t, (p + t).t = 0, |t| = r,
// t orthogonal to the axis), and each sphere's silhouette circle (center e (1 - r^2 / |e|^2),
// the tangent points from the shaded point) on the side away from the other sphere, as a
// polygon of K = kLtcCapsuleArcSides vertices between the tangent points, at the angles
// (i - 1/2) delta (delta the arc's angle / K) and the radius s rho, s such that the polygon's
// area is the arc's sector's: s^2 (K - 1) sin delta + 2 s sin(delta / 2) = K delta. Seen from
// within the cylinder's infinite extension (along the axis) the silhouette is the nearer sphere's.
const int kLtcCapsuleArcSides = 8;
IBL_FN vec3 ltcCapsuleIntegral(LtcFrame f, vec3 c, vec3 axis, float halfLength, float radius) {
  vec3 q = c - dot(c, axis) * axis;  // the axis line's point closest to the shaded point
  float distance = length(q);
  if (distance <= radius * 1.0001f)
    return ltcSphereIntegral(f, c - (dot(c, axis) > 0.0f ? halfLength : -halfLength) * axis,
                             radius);
  vec3 u = q / distance, w = cross(axis, u);
  float k = radius / distance;
  vec3 tPlus = radius * (-k * u + sqrt(1.0f - k * k) * w);
  vec3 tMinus = radius * (-k * u - sqrt(1.0f - k * k) * w);
  HorizonClippedPolygon h = horizonClippedPolygon();
  vec3 first = vec3(0.0f), previous = vec3(0.0f);
  for (int cap = 0; cap < 2; ++cap) {
    float side = cap == 0 ? -1.0f : 1.0f;
    vec3 e = c + side * halfLength * axis;  // the cap's sphere's center
    vec3 tStart = cap == 0 ? tMinus : tPlus;
    vec3 tEnd = cap == 0 ? tPlus : tMinus;
    float e2 = max(dot(e, e), radius * radius * 1.0001f);
    vec3 center = e * (1.0f - radius * radius / e2);
    vec3 x1 = e + tStart - center;
    float rho = length(x1);
    x1 = x1 / max(rho, 1e-20f);
    vec3 x2 = normalize(cross(e, x1));
    if (dot(x2, axis) * side < 0.0f) x2 = -x2;  // toward the side away from the other sphere
    vec3 y = e + tEnd - center;
    float span = atan(dot(y, x2), dot(y, x1));
    if (span < 0.0f) span += 2.0f * kPi;
    float delta = span / float(kLtcCapsuleArcSides);
    float k1 = float(kLtcCapsuleArcSides - 1) * sin(delta), sh = sin(0.5f * delta);
    float scale = (sqrt(sh * sh + k1 * float(kLtcCapsuleArcSides) * delta) - sh) / max(k1, 1e-20f);
    vec3 start = normalize(ltcToCosineSpace(f, e + tStart));
    if (cap == 0) {
      first = start;
    } else {
      h = addPolygonEdge(h, previous, start);  // the side along tPlus
    }
    previous = start;
    for (int i = 1; i <= kLtcCapsuleArcSides; ++i) {
      float a = delta * (float(i) - 0.5f);
      vec3 current =
          normalize(ltcToCosineSpace(f, center + (rho * scale) * (cos(a) * x1 + sin(a) * x2)));
      h = addPolygonEdge(h, previous, current);
      previous = current;
    }
    vec3 end = normalize(ltcToCosineSpace(f, e + tEnd));
    h = addPolygonEdge(h, previous, end);
    previous = end;
  }
  h = addPolygonEdge(h, previous, first);  // the side along tMinus
  return polygonFormFactorVector(h);
}

// The integrals of light over a shape in both frames, as (diffuse form factor vector, GGX
// fraction); c is the light's position relative to the shaded point.
IBL_FN LightIncidence ltcAreaIncidence(ShadingLight light, vec3 c, LtcFrame diffuse,
                                       LtcFrame specular) {
  float window = smoothDistanceWindow(dot(c, c), light.invSquaredRange);
  if (light.type == kLightSphere) {
    // The diffuse lobe: the exact cap formula, the same as the LTC's integral, at less cost.
    LightIncidence inc =
        ltcIncidence(diffuse, vec3(0.0f), ltcSphereIntegral(specular, c, light.radius).z, window);
    inc.diffuseDirection = normalize(c);
    inc.diffuseIlluminance = sphereIlluminanceFactor(diffuse.n, c, light.radius) * window;
    return inc;
  }
  if (light.type == kLightDisk) {
    if (dot(c, light.direction) >= 0.0f) return noIncidence(diffuse.n);  // behind it
    mat3 t = tangentFrame(light.direction);
    return ltcIncidence(diffuse, ltcDiskIntegral(diffuse, c, t[0], t[1], light.radius),
                        ltcDiskIntegral(specular, c, t[0], t[1], light.radius).z, window);
  }
  if (light.type == kLightTube) {  // the capsule's silhouette polygon
    float hl = 0.5f * light.width;
    return ltcIncidence(diffuse, ltcCapsuleIntegral(diffuse, c, light.direction, hl, light.radius),
                        ltcCapsuleIntegral(specular, c, light.direction, hl, light.radius).z,
                        window);
  }
  if (dot(c, light.direction) >= 0.0f) return noIncidence(diffuse.n);  // behind the rect
  vec3 p0 = rectCorner(light, c, 0), p1 = rectCorner(light, c, 1);
  vec3 p2 = rectCorner(light, c, 2), p3 = rectCorner(light, c, 3);
  return ltcIncidence(diffuse, ltcQuadIntegral(diffuse, p0, p1, p2, p3),
                      ltcQuadIntegral(specular, p0, p1, p2, p3).z, window);
}

IBL_END

#endif
