// API: internal (may change without notice; math shared with the shaders)
// Analytic lights in photometric units (Lagarde & de Rousiers 2014, "Moving Frostbite to
// Physically Based Rendering", section 4): the conversions from luminous power to intensity and
// luminance, the attenuation of punctual lights, and the illuminance of spheres and disks with
// the horizon handled. C++ and GLSL (see lang.h). Units: lm (luminous power), cd (intensity,
// lm/sr), lx (illuminance, lm/m^2), nit (luminance, cd/m^2); lengths in metres.
#ifndef IBL_SHARED_LIGHTS_H
#define IBL_SHARED_LIGHTS_H
#include "ibl/shared/brdf.h"
#include "ibl/shared/lang.h"
#include "ibl/shared/ltc.h"
#include "ibl/shared/sampling.h"
#include "ibl/shared/split_sum.h"

IBL_BEGIN

// --- Luminous power to intensity (punctual) and luminance (area), Frostbite section 4.2 ---

// A point light emits power phi evenly over the sphere: I = phi / 4 pi (eq. 15).
IBL_FN float pointIntensityFromPower(float phi) {
  return phi / (4.0f * kPi);
}

// A spot light of outer half-angle theta_out: the physical conversion spreads phi over its cone,
// I = phi / (2 pi (1 - cos theta_out)) (eq. 16); Frostbite's own, I = phi / pi (eq. 17), keeps
// the brightness when the cone changes and loses the power's meaning.
IBL_FN float spotIntensityFromPower(float phi, float cosOuter, bool physical) {
  return physical ? phi / (2.0f * kPi * max(1.0f - cosOuter, 1e-6f)) : phi / kPi;
}

// Lambertian emitters: L = phi / (A pi) over the emitting area A (eqs. 18-21); sphere and tube
// emit from their whole surface, disk and rectangle from one side.
IBL_FN float sphereLuminanceFromPower(float phi, float radius) {
  return phi / (4.0f * kPi * radius * radius * kPi);
}
IBL_FN float diskLuminanceFromPower(float phi, float radius) {
  return phi / (kPi * radius * radius * kPi);
}
IBL_FN float tubeLuminanceFromPower(float phi, float radius, float length) {
  return phi / ((2.0f * kPi * radius * length + 4.0f * kPi * radius * radius) * kPi);
}
IBL_FN float rectLuminanceFromPower(float phi, float width, float height) {
  return phi / (width * height * kPi);
}

// --- Punctual attenuation, Frostbite section 4.7.1 (after Karis 2013) ---

// The smooth window that takes the inverse-square law to zero at the influence radius:
// saturate(1 - (d / radius)^4)^2, from d^2 and 1 / radius^2 (0: no window, always 1).
IBL_FN float smoothDistanceWindow(float squaredDistance, float invSquaredRadius) {
  float factor = squaredDistance * invSquaredRadius;
  float smoothFactor = clamp(1.0f - factor * factor, 0.0f, 1.0f);
  return smoothFactor * smoothFactor;
}

// 1 / d^2 (d at least 1 cm, a punctual light's size) times the window.
IBL_FN float distanceAttenuation(float squaredDistance, float invSquaredRadius) {
  return smoothDistanceWindow(squaredDistance, invSquaredRadius) /
         max(squaredDistance, 0.01f * 0.01f);
}

// A spot's angular falloff: 0 outside the outer cone, 1 inside the inner one, and between them
// the square of a linear ramp in cos(angle) (cosAngle: between the spot's direction and the
// direction from the light to the point).
IBL_FN float spotAngleAttenuation(float cosAngle, float cosInner, float cosOuter) {
  float scale = 1.0f / max(0.001f, cosInner - cosOuter);
  float t = clamp((cosAngle - cosOuter) * scale, 0.0f, 1.0f);
  return t * t;
}

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

// ShadingLight.type.
const int kLightPoint = 0;
const int kLightSpot = 1;
const int kLightSun = 2;
const int kLightSphere = 3;
const int kLightDisk = 4;
const int kLightTube = 5;
const int kLightRect = 6;

// A light as the shading reads it, in world space and photometric units.
struct ShadingLight {
  int type;
  vec3 position;   // punctual and area lights; tube: the segment's center; rect: its center
  vec3 direction;  // spot: where it shines; sun: toward the sun; disk, rect: the emitting side;
                   // tube: the segment's axis (unit vectors)
  vec3 up;         // rect: along its height (unit, orthogonal to direction)
  vec3 color;      // linear RGB x cd (point, spot), lx (sun) or nit (area lights)
  float radius;    // sphere, disk, tube; sun: the angular radius in radians
  float width;     // rect; tube: the segment's length
  float height;    // rect
  float cosInner;  // spot
  float cosOuter;  // spot
  float invSquaredRange;  // 1 / influence radius^2; 0: no window
};

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

// --- IES profiles: where a direction falls on the photometric web (LM-63 type C) ---

// The profile's nadir (vertical angle 0): a spot's direction, straight down (-Y) for a point.
IBL_FN vec3 iesNadir(ShadingLight light) {
  return light.type == kLightSpot ? light.direction : vec3(0.0f, -1.0f, 0.0f);
}
// The horizontal angle 0 (the profile's 0-degree plane): +X made orthogonal to the nadir (-Z
// when the nadir is close to X).
IBL_FN vec3 iesHorizontalAxis(vec3 nadir) {
  vec3 ref = abs(nadir.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 0.0f, -1.0f);
  return normalize(ref - dot(ref, nadir) * nadir);
}
// The viewer's tables of IES profiles: each profile's candela over its peak at vertical angles
// 0..180 degrees in kIesTableRows rows and horizontal angles 0..360 in kIesTableColumns columns
// (2 and 5 degrees apart), read bilinearly (src/gpu/scene_renderer.cpp writes them).
const int kIesTableRows = 91;
const int kIesTableColumns = 73;

// (vertical, horizontal) angles in degrees of the unit direction w leaving the light: vertical
// from the nadir, horizontal counterclockwise seen from above (h90 = h0 x nadir) in [0, 360).
IBL_FN vec2 iesAngles(vec3 nadir, vec3 w) {
  vec3 h0 = iesHorizontalAxis(nadir);
  vec3 h90 = cross(h0, nadir);
  float vertical = acos(clamp(dot(w, nadir), -1.0f, 1.0f)) * (180.0f / kPi);
  float horizontal = atan(dot(w, h90), dot(w, h0)) * (180.0f / kPi);
  if (horizontal < 0.0f) horizontal += 360.0f;
  return vec2(vertical, horizontal);
}

// --- Rays meeting the emitting shapes: what the camera sees of area lights and the sun, and
// where the reference's samples land (src/render/light_sampling.cpp) ---

// Distances along a ray: a miss is negative, the sun (at infinity) kSunDistance.
const float kSunDistance = 1e30f;

// The nearest t > 0 where the ray o + t w (w unit) meets the sphere, or -1. The discriminant
// written as r^2 - |oc - (oc.w) w|^2, accurate for distant spheres.
IBL_FN float raySphereDistance(vec3 o, vec3 w, vec3 center, float radius) {
  vec3 oc = o - center;
  float b = dot(oc, w);
  vec3 perp = oc - b * w;
  float disc = radius * radius - dot(perp, perp);
  if (disc < 0.0f) return -1.0f;
  float sq = sqrt(disc);
  float t0 = -b - sq, t1 = -b + sq;
  if (t0 > 0.0f) return t0;
  return t1 > 0.0f ? t1 : -1.0f;
}

// The t > 0 where the ray meets the plane through c with normal m, or -1.
IBL_FN float rayPlaneDistance(vec3 o, vec3 w, vec3 c, vec3 m) {
  float wm = dot(w, m);
  if (abs(wm) < 1e-12f) return -1.0f;
  float t = dot(c - o, m) / wm;
  return t > 0.0f ? t : -1.0f;
}

// The nearest t > 0 where the ray meets a capsule (the segment center +- axis length / 2, radius
// r), or -1: the cylinder within the segment's span, then the two end spheres outside it.
IBL_FN float rayCapsuleDistance(vec3 o, vec3 w, vec3 center, vec3 axis, float len, float radius) {
  float hl = 0.5f * len;
  float best = -1.0f;
  vec3 oc = o - center;
  vec3 op = oc - dot(oc, axis) * axis, wp = w - dot(w, axis) * axis;
  float qa = dot(wp, wp), qb = dot(op, wp), qc = dot(op, op) - radius * radius;
  if (qa > 1e-12f) {
    float disc = qb * qb - qa * qc;
    if (disc >= 0.0f) {
      float sq = sqrt(disc);
      float tNear = (-qb - sq) / qa, tFar = (-qb + sq) / qa;
      if (tNear > 0.0f && abs(dot(oc + tNear * w, axis)) <= hl)
        best = tNear;
      else if (tFar > 0.0f && abs(dot(oc + tFar * w, axis)) <= hl)
        best = tFar;
    }
  }
  for (int i = 0; i < 2; ++i) {
    float end = i == 0 ? -hl : hl;
    vec3 endCenter = center + end * axis;
    float t = raySphereDistance(o, w, endCenter, radius);
    if (t < 0.0f || (best >= 0.0f && t >= best)) continue;
    // A cap's point within the cylinder's span is not on the capsule's surface.
    float along = dot(o + t * w - endCenter, axis);
    if ((end > 0.0f && along < 0.0f) || (end < 0.0f && along > 0.0f)) continue;
    best = t;
  }
  return best;
}

// Where the ray (o, unit w) meets the light's emitting shape: its distance (negative: missed;
// the sun: kSunDistance while w is within its disk). Punctual lights are never met.
IBL_FN float emitterDistance(ShadingLight light, vec3 o, vec3 w) {
  if (light.type == kLightSun)
    return dot(light.direction, w) >= cos(light.radius) ? kSunDistance : -1.0f;
  if (light.type == kLightSphere) return raySphereDistance(o, w, light.position, light.radius);
  if (light.type == kLightTube)
    return rayCapsuleDistance(o, w, light.position, light.direction, light.width, light.radius);
  if (light.type != kLightDisk && light.type != kLightRect) return -1.0f;
  float t = rayPlaneDistance(o, w, light.position, light.direction);
  if (t < 0.0f) return -1.0f;
  vec3 q = o + t * w - light.position;
  if (light.type == kLightDisk) return dot(q, q) <= light.radius * light.radius ? t : -1.0f;
  vec3 left = cross(light.up, light.direction);
  return abs(dot(q, left)) <= 0.5f * light.width && abs(dot(q, light.up)) <= 0.5f * light.height
             ? t
             : -1.0f;
}

// The luminance the ray sees on the emitter it met (no distance window): area lights their
// luminance (the back of a disk or rect black), the sun E / (pi sin^2 sigma) (Frostbite
// section 4.7.1: E = L pi sin^2 sigma on a surface facing it).
IBL_FN vec3 emitterRadiance(ShadingLight light, vec3 w) {
  if (light.type == kLightSun) {
    float sinSigma = sin(light.radius);
    return light.color / (kPi * sinSigma * sinSigma);
  }
  if ((light.type == kLightDisk || light.type == kLightRect) && dot(w, light.direction) >= 0.0f)
    return vec3(0.0f);
  return light.color;
}

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

// The light's incidence at a point (position p, unit normal n, unit view v, perceptual
// roughness). s.dominantDirections: the specular representative point follows the area dominant
// direction; s.ltcAreaLights: spheres, disks, tubes and rects through LTCs, with `ltc` the GGX
// table's entry at (roughness, n.v) (ltcTableCoordinates).
IBL_FN LightIncidence lightIncidence(ShadingLight light, vec3 p, vec3 n, vec3 v, float roughness,
                                     SplitSumSwitches s, vec4 ltc) {
  vec3 c = light.position - p;
  if (s.ltcAreaLights && light.type >= kLightSphere)
    return ltcAreaIncidence(light, c, ltcFrame(n, v, vec4(1.0f, 0.0f, 0.0f, 1.0f)),
                            ltcFrame(n, v, ltc));
  float alpha = max(alphaFromRoughness(roughness), 1e-3f);
  vec3 r = 2.0f * dot(n, v) * n - v;
  if (s.dominantDirections) r = specularDominantDirectionArea(n, r, alpha);
  if (light.type == kLightSun) return sunIncidence(light, n, r, alpha);
  if (light.type == kLightSphere) return sphereIncidence(light, c, n, r, alpha);
  if (light.type == kLightDisk) return diskIncidence(light, c, n, r, alpha);
  if (light.type == kLightRect) return rectIncidence(light, c, n, r, alpha);
  if (light.type == kLightTube) return tubeIncidence(light, c, n, r, alpha);
  return punctualIncidence(light, c, n);
}

// The sheen lobe (KHR_materials_sheen) lit by one light: sheenColor D_charlie V times the
// illuminance, V the visibility model `visibility` (sheenVisibility in brdf.h), from the light's
// diffuse representative direction (the Charlie lobe is broad, like the diffuse one; for
// punctual lights and the sun this is exact).
IBL_FN vec3 sheenLightRadiance(vec3 sheenColor, float sheenAlpha, int visibility, vec3 n, vec3 v,
                               LightIncidence inc) {
  vec3 l = inc.diffuseDirection;
  float NoL = dot(n, l);
  if (inc.diffuseIlluminance <= 0.0f || NoL <= 0.0f) return vec3(0.0f);
  float NoV = max(dot(n, v), 1e-4f);
  vec3 h = normalize(v + l);
  return sheenColor * (charlieDistribution(clamp(dot(n, h), 0.0f, 1.0f), sheenAlpha) *
                       sheenVisibility(visibility, NoV, NoL, sheenAlpha) * inc.diffuseIlluminance);
}

// The radiance the standard material (the BRDF of the IBL path) reflects toward v from a light's
// incidence, per unit of the light's color: diffuse (Disney or Lambert) x the diffuse
// illuminance, GGX x the specular illuminance, with the multiple-scattering compensation of the
// split sum (dfg: the DFG table's A, B at n.v).
IBL_FN vec3 lightRadiance(SplitSumMaterial m, vec3 n, vec3 v, LightIncidence inc, vec2 dfg,
                          SplitSumSwitches s) {
  float alpha = max(alphaFromRoughness(m.roughness), 1e-3f);
  vec3 diffuseColor = m.baseColor * (1.0f - m.metallic);
  vec3 f0 = mix(vec3(0.04f), m.baseColor, m.metallic);
  float NoV = max(dot(n, v), 1e-4f);
  vec3 color = vec3(0.0f);
  if (s.terms != 2 && inc.diffuseIlluminance > 0.0f) {
    vec3 l = inc.diffuseDirection;
    float fd = 1.0f;
    if (s.disneyDiffuse)
      fd = disneyDiffuseRenormalized(NoV, clamp(dot(n, l), 0.0f, 1.0f), dot(l, normalize(v + l)),
                                     m.roughness);
    color += diffuseColor * (fd / kPi * inc.diffuseIlluminance);
  }
  if (s.terms != 1 && inc.specularLobeFraction > 0.0f) {
    // The LTC's fraction of the lobe, times the lobe's directional albedo with Schlick's Fresnel
    // (the DFG table's F0 A + B, as the split sum scales the prefiltered map).
    vec3 specular = (f0 * dfg.x + vec3(fresnelF90(f0, s.specularMicroOcclusion) * dfg.y)) *
                    inc.specularLobeFraction;
    if (s.multipleScattering) specular *= multipleScatteringCompensation(f0, dfg);
    color += specular;
  } else if (s.terms != 1 && inc.specularIlluminance > 0.0f) {
    vec3 l = inc.specularDirection;
    vec3 h = normalize(v + l);
    float NoL = max(dot(n, l), 1e-4f);
    float dv = ggxDistribution(clamp(dot(n, h), 0.0f, 1.0f), alpha) * inc.specularNormalization *
               smithGgxCorrelatedVisibility(NoV, NoL, alpha);
    vec3 specular =
        dv * fresnelSchlick(f0, fresnelF90(f0, s.specularMicroOcclusion), max(dot(v, h), 0.0f)) *
        inc.specularIlluminance;
    if (s.multipleScattering) specular *= multipleScatteringCompensation(f0, dfg);
    color += specular;
  }
  return color;
}

IBL_END

#endif
