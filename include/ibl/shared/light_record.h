// API: internal (may change without notice; math shared with the shaders)
// An analytic light as the shading reads it (ShadingLight and its types), the record in which the
// GPU holds it (five vec4 per light, written by the C++ side and read by the shaders), where a
// direction falls on its IES profile, and where a ray meets its emitting shape: what both the
// real-time shading (lights.h) and the reference (light_sampling.h) read of a light. C++ and GLSL
// (see lang.h).
#ifndef IBL_SHARED_LIGHT_RECORD_H
#define IBL_SHARED_LIGHT_RECORD_H
#include "ibl/shared/lang.h"

IBL_BEGIN

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

// --- The GPU's light record: five vec4 per light, the layout of the viewer's light buffer
// (view/frame.glsl's Lights, src/gpu/scene_upload.cpp) and of the GPU path tracer's
// (render/path_trace.comp's sceneData, src/gpu/path_tracer.cpp) ---
//
//   vec4 | xyz                                  | w
//   0    | position                             | type (a kLight... value)
//   1    | direction                            | radius
//   2    | up                                   | width
//   3    | color                                | height
//   4    | cosInner, cosOuter, invSquaredRange  | IES profile: its table's index, -1 for none
//
// The profile's table is the renderer's own: the viewer's holds each profile over its peak (the
// color then carries the peak), the path tracer's the candela times the light's scale.
const int kLightRecordVec4s = 5;
struct LightRecord {
  vec4 positionType;
  vec4 directionRadius;
  vec4 upWidth;
  vec4 colorHeight;
  vec4 coneRangeProfile;
};

// The record of light `l`; `profile` the index of its IES profile's table, -1 for none.
IBL_FN LightRecord packLight(ShadingLight l, float profile) {
  LightRecord r;
  r.positionType = vec4(l.position, float(l.type));
  r.directionRadius = vec4(l.direction, l.radius);
  r.upWidth = vec4(l.up, l.width);
  r.colorHeight = vec4(l.color, l.height);
  r.coneRangeProfile = vec4(l.cosInner, l.cosOuter, l.invSquaredRange, profile);
  return r;
}

// The light that record `r` holds (packLight's inverse).
IBL_FN ShadingLight unpackLight(LightRecord r) {
  ShadingLight l;
  l.type = int(r.positionType.w);
  l.position = vec3(r.positionType);
  l.direction = vec3(r.directionRadius);
  l.radius = r.directionRadius.w;
  l.up = vec3(r.upWidth);
  l.width = r.upWidth.w;
  l.color = vec3(r.colorHeight);
  l.height = r.colorHeight.w;
  l.cosInner = r.coneRangeProfile.x;
  l.cosOuter = r.coneRangeProfile.y;
  l.invSquaredRange = r.coneRangeProfile.z;
  return l;
}

// The index of the IES profile's table that record `r` names, -1 for none.
IBL_FN float lightRecordProfile(LightRecord r) {
  return r.coneRangeProfile.w;
}

#ifdef __cplusplus
// Record `r` as the C++ side's buffers of vec4 hold it: its five vec4 at out[0..4].
inline void storeLightRecord(const LightRecord& r, vec4* out) {
  out[0] = r.positionType;
  out[1] = r.directionRadius;
  out[2] = r.upWidth;
  out[3] = r.colorHeight;
  out[4] = r.coneRangeProfile;
}
#endif

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
// (2 and 5 degrees apart), read bilinearly (src/gpu/scene_upload.cpp writes them).
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

IBL_END

#endif
