// API: internal (may change without notice; math shared with the shaders)
// The real-time approximations of the analytic lights after Frostbite (Lagarde & de Rousiers
// 2014, "Moving Frostbite to Physically Based Rendering", section 4.7) and Karis 2013 ("Real
// Shading in Unreal Engine 4"): the illuminance of spheres and disks with the horizon handled,
// the structured sampling of rects and tubes, the representative points and widened lobes of
// the specular peak, as the incidence each light type delivers to a point. C++ and GLSL (see
// lang.h); the dispatch among them, and the LTC alternative, are lights.h's.
#ifndef IBL_SHARED_LIGHTS_FROSTBITE_H
#define IBL_SHARED_LIGHTS_FROSTBITE_H
#include "ibl/shared/lang.h"
#include "ibl/shared/light_record.h"
#include "ibl/shared/light_units.h"
#include "ibl/shared/sampling.h"

IBL_BEGIN

// --- Sphere and disk illuminance, Frostbite section 4.7.2 ---

// The illuminance of a uniform spherical cap of luminance 1 (a sphere, or a disk facing the
// point) on a surface whose normal makes angle theta with the cap's center: pi sin^2(sigma)
// cos(theta) while the cap is all above the horizon, the exact integral of the cosine over the
// visible part of the cap while it straddles it (Snyder 1996's form factor, as Frostbite's
// Listing 9 writes it), 0 below. sinSigmaSqr: sin^2 of the cap's half-angle, r^2 / d^2 for a
// sphere. cosTheta is not clamped.
IBL_FN float illuminanceSphereOrDisk(float cosTheta, float sinSigmaSqr) {
  float illuminance;
  if (cosTheta * cosTheta > sinSigmaSqr) {
    illuminance = kPi * sinSigmaSqr * clamp(cosTheta, 0.0f, 1.0f);
  } else {
    float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
    float x = sqrt(1.0f / sinSigmaSqr - 1.0f);  // cot(sigma); d / r for a disk
    float y = -x * (cosTheta / sinTheta);
    float sinThetaSqrtY = sinTheta * sqrt(max(1.0f - y * y, 0.0f));
    illuminance = (cosTheta * acos(y) - x * sinThetaSqrtY) * sinSigmaSqr + atan(sinThetaSqrtY / x);
  }
  return max(illuminance, 0.0f);
}

// Illuminance per unit luminance of a sphere of radius r whose center is at `toLight` from the
// shaded point (normal n): exact, horizon included. The sphere may not reach the point.
IBL_FN float sphereIlluminanceFactor(vec3 n, vec3 toLight, float radius) {
  float squaredDistance = dot(toLight, toLight);
  float cosTheta = clamp(dot(n, toLight) / sqrt(squaredDistance), -1.0f, 1.0f);
  float sinSigmaSqr = min(radius * radius / squaredDistance, 0.9999f);
  return illuminanceSphereOrDisk(cosTheta, sinSigmaSqr);
}

// Illuminance per unit luminance of a one-sided disk of radius r centered at `toLight` from the
// shaded point, emitting along diskNormal: Frostbite's approximation, the disk treated as one
// facing the point (a cap of sin^2 sigma = r^2 / (r^2 + d^2)) and weighted by how much it faces
// the point, saturate(diskNormal . -l). Not exact: its error against quadrature is measured.
IBL_FN float diskIlluminanceFactor(vec3 n, vec3 toLight, float radius, vec3 diskNormal) {
  float squaredDistance = dot(toLight, toLight);
  vec3 l = toLight / sqrt(squaredDistance);
  float r2 = radius * radius;
  float sinSigmaSqr = r2 / (r2 + max(r2, squaredDistance));
  return illuminanceSphereOrDisk(dot(n, l), sinSigmaSqr) * clamp(dot(diskNormal, -l), 0.0f, 1.0f);
}

// --- The real-time approximations (Frostbite section 4.7; Karis 2013) ---

// What a light delivers to a point, split as the approximations split it: the illuminance
// (per unit of ShadingLight.color) the diffuse lobe receives and the direction it is evaluated
// toward; the same for the specular lobe, whose GGX peak is scaled by specularNormalization
// (Karis 2013's energy normalization of the representative point). Or, for an area light
// through LTCs, the fraction of the normalized GGX lobe the light covers (per unit luminance),
// which the DFG table's Fresnel terms scale: specularLobeFraction, negative when unused.
struct LightIncidence {
  vec3 diffuseDirection;
  float diffuseIlluminance;
  vec3 specularDirection;
  float specularIlluminance;
  float specularNormalization;
  float specularLobeFraction;
};

// No light from direction l (what each approximation starts from).
IBL_FN LightIncidence noIncidence(vec3 l) {
  LightIncidence inc;
  inc.diffuseDirection = l;
  inc.diffuseIlluminance = 0.0f;
  inc.specularDirection = l;
  inc.specularIlluminance = 0.0f;
  inc.specularNormalization = 1.0f;
  inc.specularLobeFraction = -1.0f;
  return inc;
}

// The solid angle of the quadrilateral p0 p1 p2 p3 (in order around it) seen from the origin:
// the spherical polygon's angle excess (Frostbite section 4.7.2.5, after Urena et al. 2013).
IBL_FN float quadSolidAngle(vec3 p0, vec3 p1, vec3 p2, vec3 p3) {
  vec3 n0 = normalize(cross(p0, p1));
  vec3 n1 = normalize(cross(p1, p2));
  vec3 n2 = normalize(cross(p2, p3));
  vec3 n3 = normalize(cross(p3, p0));
  float g0 = acos(clamp(dot(-n0, n1), -1.0f, 1.0f));
  float g1 = acos(clamp(dot(-n1, n2), -1.0f, 1.0f));
  float g2 = acos(clamp(dot(-n2, n3), -1.0f, 1.0f));
  float g3 = acos(clamp(dot(-n3, n0), -1.0f, 1.0f));
  return max(g0 + g1 + g2 + g3 - 2.0f * kPi, 0.0f);
}

// Frostbite's structured sampling of a quadrilateral's illuminance (section 4.7.2.5): its solid
// angle times the mean clamped cosine of its four corners and its center (the clamp handles
// the horizon). Corners relative to the shaded point, n its normal. Returns (E, solid angle).
IBL_FN vec2 quadIlluminanceStructured(vec3 n, vec3 p0, vec3 p1, vec3 p2, vec3 p3, vec3 center) {
  float omega = quadSolidAngle(p0, p1, p2, p3);
  float c = clamp(dot(normalize(p0), n), 0.0f, 1.0f) + clamp(dot(normalize(p1), n), 0.0f, 1.0f) +
            clamp(dot(normalize(p2), n), 0.0f, 1.0f) + clamp(dot(normalize(p3), n), 0.0f, 1.0f) +
            clamp(dot(normalize(center), n), 0.0f, 1.0f);
  return vec2(omega * 0.2f * c, omega);
}

// Karis 2013's normalization of a GGX peak widened by a source of angular half-extent
// `halfExtent` (radians, about size / (2 distance)) in one direction: alpha / alpha', with
// alpha' = saturate(alpha + halfExtent / 2). A round source widens both directions (square it).
IBL_FN float widenedLobeNormalization(float alpha, float halfExtent) {
  return alpha / clamp(alpha + 0.5f * halfExtent, 1e-4f, 1.0f);
}

// The illuminance the specular lobe is given: for a sharp lobe, the light's solid angle times
// the cosine toward the representative point (what the lobe sees), for a wide lobe the
// horizon-aware illuminance the diffuse lobe receives (the representative point says little
// then, and it may sit above the horizon while most of the light is below); between them, a
// blend by alpha (ours, measured in docs/lights.md).
IBL_FN float specularIlluminanceBlend(float towardPoint, float diffuseIlluminance, float alpha) {
  return mix(towardPoint, diffuseIlluminance, alpha);
}

// Frostbite's dominant direction for area lights (section 4.7.5): a lerp from n toward the
// mirror direction r by 1 - alpha (the GGX alpha: the document's code calls it roughness; with
// the perceptual roughness, smooth surfaces lose their highlights, measured).
IBL_FN vec3 specularDominantDirectionArea(vec3 n, vec3 r, float alpha) {
  return normalize(mix(n, r, 1.0f - alpha));
}

// The point of a sphere (center c, radius, relative to the shaded point) closest to the ray
// from the shaded point along unit r: the representative point of Karis 2013 (eq. 10).
IBL_FN vec3 closestPointOnSphereToRay(vec3 c, float radius, vec3 r) {
  vec3 centerToRay = dot(c, r) * r - c;
  float len = max(length(centerToRay), 1e-7f);
  return c + centerToRay * clamp(radius / len, 0.0f, 1.0f);
}

// The point of a segment a..b (relative to the shaded point) closest to the ray along unit r
// (Karis 2013, eq. 13).
IBL_FN vec3 closestPointOnSegmentToRay(vec3 a, vec3 b, vec3 r) {
  vec3 ab = b - a;
  float rab = dot(r, ab);
  float t = (dot(r, a) * rab - dot(a, ab)) / max(dot(ab, ab) - rab * rab, 1e-12f);
  return a + clamp(t, 0.0f, 1.0f) * ab;
}

// Where the ray along unit r from the shaded point meets the plane through c (relative to the
// point) with normal m, as an offset from c within the plane; a ray parallel to or leaving the
// plane gives the far point of r's projection on it.
IBL_FN vec3 rayPlaneOffset(vec3 c, vec3 m, vec3 r) {
  float rm = dot(r, m);
  float t = dot(c, m) / (abs(rm) > 1e-6f ? rm : 1e-6f);
  vec3 rInPlane = r - rm * m;
  if (t > 0.0f) return t * r - c;
  return rInPlane * 1e6f - (c - dot(c, m) * m);
}

// A point or spot light: toLight from the shaded point to the light (world units), n the unit
// normal; the inverse square, the range window and the spot's cone applied.
IBL_FN LightIncidence punctualIncidence(ShadingLight light, vec3 toLight, vec3 n) {
  float d2 = dot(toLight, toLight);
  vec3 l = toLight / sqrt(max(d2, 1e-20f));
  LightIncidence inc = noIncidence(l);
  float e = distanceAttenuation(d2, light.invSquaredRange) * clamp(dot(n, l), 0.0f, 1.0f);
  if (light.type == kLightSpot)
    e *= spotAngleAttenuation(dot(light.direction, -l), light.cosInner, light.cosOuter);
  inc.diffuseIlluminance = e;
  inc.specularIlluminance = e;
  return inc;
}

// The sun as a disk (Frostbite section 4.7.1, listing 7): diffuse toward its center, specular
// toward the disk's point closest to r.
IBL_FN LightIncidence sunIncidence(ShadingLight light, vec3 n, vec3 r, float alpha) {
  vec3 d = light.direction;
  LightIncidence inc = noIncidence(d);
  float sinSigma = sin(light.radius), cosSigma = cos(light.radius);
  float DoR = dot(d, r);
  vec3 s = r - DoR * d;
  vec3 l =
      DoR < cosSigma && dot(s, s) > 1e-12f ? normalize(cosSigma * d + normalize(s) * sinSigma) : r;
  inc.diffuseIlluminance = clamp(dot(n, d), 0.0f, 1.0f);
  inc.specularDirection = l;
  inc.specularIlluminance = clamp(dot(n, l), 0.0f, 1.0f);
  float w = widenedLobeNormalization(alpha, sinSigma);
  inc.specularNormalization = w * w;
  return inc;
}

// The area lights' incidence (lightIncidence without LTCs): c the light's center relative to
// the shaded point, n the unit normal, r the specular lobe's unit direction (the reflected view
// or its dominant direction), alpha the GGX alpha.
IBL_FN LightIncidence sphereIncidence(ShadingLight light, vec3 c, vec3 n, vec3 r, float alpha) {
  float d2 = dot(c, c);
  float window = smoothDistanceWindow(d2, light.invSquaredRange);
  float sinSigmaSqr = min(light.radius * light.radius / d2, 0.9999f);
  LightIncidence inc = noIncidence(c / sqrt(d2));
  inc.diffuseIlluminance = sphereIlluminanceFactor(n, c, light.radius) * window;
  vec3 l = normalize(closestPointOnSphereToRay(c, light.radius, r));
  inc.specularDirection = l;
  inc.specularIlluminance = specularIlluminanceBlend(
      kPi * sinSigmaSqr * clamp(dot(n, l), 0.0f, 1.0f) * window, inc.diffuseIlluminance, alpha);
  float w = widenedLobeNormalization(alpha, light.radius / sqrt(d2));
  inc.specularNormalization = w * w;
  return inc;
}

// As sphereIncidence, for a disk.
IBL_FN LightIncidence diskIncidence(ShadingLight light, vec3 c, vec3 n, vec3 r, float alpha) {
  float d2 = dot(c, c);
  float window = smoothDistanceWindow(d2, light.invSquaredRange);
  vec3 m = light.direction;
  vec3 lc = c / sqrt(d2);
  LightIncidence inc = noIncidence(lc);
  inc.diffuseIlluminance = diskIlluminanceFactor(n, c, light.radius, m) * window;
  vec3 q = rayPlaneOffset(c, m, r);
  float ql = length(q);
  vec3 onDisk = c + (ql > light.radius ? q * (light.radius / ql) : q);
  vec3 l = normalize(onDisk);
  float r2 = light.radius * light.radius;
  float facing = clamp(dot(m, -lc), 0.0f, 1.0f);
  inc.specularDirection = l;
  inc.specularIlluminance = specularIlluminanceBlend(
      kPi * r2 / (r2 + d2) * facing * clamp(dot(n, l), 0.0f, 1.0f) * window, inc.diffuseIlluminance,
      alpha);
  float w = widenedLobeNormalization(alpha, light.radius / sqrt(d2));
  inc.specularNormalization = w * w;
  return inc;
}

// The corners of a rect light, relative to the shaded point (its center at c), in order around
// it; corner(i) for i = 0..3.
IBL_FN vec3 rectCorner(ShadingLight light, vec3 c, int i) {
  vec3 left = cross(light.up, light.direction);
  float sx = i < 2 ? -0.5f : 0.5f, sy = i == 0 || i == 3 ? 0.5f : -0.5f;
  return c + left * (sx * light.width) + light.up * (sy * light.height);
}

// As sphereIncidence, for a rect.
IBL_FN LightIncidence rectIncidence(ShadingLight light, vec3 c, vec3 n, vec3 r, float alpha) {
  float d2 = dot(c, c);
  float window = smoothDistanceWindow(d2, light.invSquaredRange);
  vec3 m = light.direction;
  vec3 up = light.up;
  vec3 left = cross(up, m);
  float hw = 0.5f * light.width, hh = 0.5f * light.height;
  LightIncidence inc = noIncidence(c / sqrt(d2));
  if (dot(c, m) >= 0.0f) return inc;  // behind the emitting side
  vec2 e = quadIlluminanceStructured(n, rectCorner(light, c, 0), rectCorner(light, c, 1),
                                     rectCorner(light, c, 2), rectCorner(light, c, 3), c);
  inc.diffuseIlluminance = e.x * window;
  vec3 q = rayPlaneOffset(c, m, r);
  vec3 onRect = c + left * clamp(dot(q, left), -hw, hw) + up * clamp(dot(q, up), -hh, hh);
  vec3 l = normalize(onRect);
  inc.specularDirection = l;
  inc.specularIlluminance = specularIlluminanceBlend(e.y * clamp(dot(n, l), 0.0f, 1.0f) * window,
                                                     inc.diffuseIlluminance, alpha);
  float d = sqrt(d2);
  inc.specularNormalization =
      widenedLobeNormalization(alpha, hw / d) * widenedLobeNormalization(alpha, hh / d);
  return inc;
}

// The tube (a capsule) as Frostbite splits it (section 4.7.2.6): its cylinder as the rectangle
// facing the point, its two caps as one sphere at the segment's point closest to the shaded
// point (here with the exact, horizon-aware sphere formula); the specular toward the capsule's
// point closest to r (Karis 2013, eqs. 13 and 10).
// The tube's cylinder as Frostbite approximates it: the rectangle through its axis that faces
// the shaded point (length x diameter), as a rect light centered at c (relative to the point).
IBL_FN ShadingLight tubeFacingRect(ShadingLight tube, vec3 c) {
  vec3 axis = tube.direction;
  vec3 onLine = c - dot(c, axis) * axis;  // the closest point of the infinite line
  float distance = length(onLine);
  ShadingLight rect = tube;
  rect.direction = distance > 1e-6f ? -onLine / distance : tangentFrame(axis)[0];
  rect.up = axis;
  rect.width = 2.0f * tube.radius;
  rect.height = tube.width;
  return rect;
}
// The segment's point closest to the shaded point, relative to it: where Frostbite puts the
// sphere that stands for the tube's two caps.
IBL_FN vec3 tubeCapsCenter(ShadingLight tube, vec3 c) {
  float hl = 0.5f * tube.width;
  return c + tube.direction * clamp(-dot(c, tube.direction), -hl, hl);
}

// As sphereIncidence, for a tube.
IBL_FN LightIncidence tubeIncidence(ShadingLight light, vec3 c, vec3 n, vec3 r, float alpha) {
  float d2 = dot(c, c);
  float window = smoothDistanceWindow(d2, light.invSquaredRange);
  vec3 axis = light.direction;
  float hl = 0.5f * light.width;
  vec3 a = c - axis * hl, b = c + axis * hl;
  ShadingLight rect = tubeFacingRect(light, c);
  // A tube of length 0 is its caps alone (the rect's solid angle would be 0 / 0).
  vec2 e = hl > 0.0f ? quadIlluminanceStructured(n, rectCorner(rect, c, 0), rectCorner(rect, c, 1),
                                                 rectCorner(rect, c, 2), rectCorner(rect, c, 3), c)
                     : vec2(0.0f);
  vec3 onSegment = tubeCapsCenter(light, c);
  float capsE = sphereIlluminanceFactor(n, onSegment, light.radius);
  LightIncidence inc = noIncidence(c / sqrt(d2));
  inc.diffuseIlluminance = (e.x + capsE) * window;
  vec3 l =
      normalize(closestPointOnSphereToRay(closestPointOnSegmentToRay(a, b, r), light.radius, r));
  float s2 = dot(onSegment, onSegment);
  float capsOmega = kPi * min(light.radius * light.radius / s2, 0.9999f);
  inc.specularDirection = l;
  inc.specularIlluminance = specularIlluminanceBlend(
      (e.y + capsOmega) * clamp(dot(n, l), 0.0f, 1.0f) * window, inc.diffuseIlluminance, alpha);
  float ds = sqrt(s2);
  inc.specularNormalization = widenedLobeNormalization(alpha, light.radius / ds) *
                              widenedLobeNormalization(alpha, (light.radius + hl) / ds);
  return inc;
}

IBL_END

#endif
