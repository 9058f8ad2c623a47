// API: internal (may change without notice; math shared with the shaders)
// The reference's sampling of the analytic lights' emitting shapes, for the CPU path tracer
// (src/render/light_sampling.cpp) and the GPU's (shaders/render/path_trace.comp): a direction
// toward the light seen from a point, and the density per solid angle of any direction under
// that sampling (for multiple importance sampling with the BRDF). C++ and GLSL (see lang.h).
//
//   sun, sphere  uniform in the cone the disk or sphere subtends (a spherical cap)
//   disk, tube   uniform over the emitting area (a capsule's front half is what is seen)
//   rect         uniform in the solid angle (spherical rectangles, Urena et al. 2013)
//
// Punctual lights (a delta, with their IES profiles) are the callers'.
#ifndef IBL_SHARED_LIGHT_SAMPLING_H
#define IBL_SHARED_LIGHT_SAMPLING_H
#include "ibl/shared/lang.h"
#include "ibl/shared/light_record.h"
#include "ibl/shared/light_units.h"
#include "ibl/shared/sampling.h"

IBL_BEGIN

// --- Spherical caps: the sun and spheres ---

struct LightCap {
  vec3 axis;             // unit, toward the cap's center
  float oneMinusCosMax;  // 1 - cos(half-angle), written to keep small caps exact
  bool valid;            // false: the point is inside the sphere
};

// The cap of half-angle asin(sqrt(sin2)) around `axis`.
IBL_FN LightCap lightCapOf(vec3 axis, float sin2) {
  LightCap cap;
  cap.axis = axis;
  cap.valid = sin2 < 1.0f;
  cap.oneMinusCosMax = cap.valid ? sin2 / (1.0f + sqrt(1.0f - sin2)) : 0.0f;
  return cap;
}

// The cap a sphere light subtends from p.
IBL_FN LightCap sphereLightCap(ShadingLight l, vec3 p) {
  vec3 c = l.position - p;
  float d2 = dot(c, c);
  return lightCapOf(c / sqrt(d2), l.radius * l.radius / d2);
}

// The sun's disk (radius: its angular radius).
IBL_FN LightCap sunLightCap(ShadingLight l) {
  float s = sin(l.radius);
  return lightCapOf(l.direction, s * s);
}

// Uniform in the cap (pbrt-v4 4th ed., section 12.2.3): cos(theta) uniform in [cos max, 1].
IBL_FN vec3 sampleLightCap(LightCap cap, vec2 xi) {
  float oneMinusCos = xi.x * cap.oneMinusCosMax;
  float cosTheta = 1.0f - oneMinusCos;
  float sinTheta = sqrt(max(0.0f, oneMinusCos * (2.0f - oneMinusCos)));
  float phi = 2.0f * kPi * xi.y;
  return normalize(tangentFrame(cap.axis) *
                   vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta));
}

IBL_FN float lightCapPdf(LightCap cap) {
  return 1.0f / (2.0f * kPi * cap.oneMinusCosMax);
}

IBL_FN bool inLightCap(LightCap cap, vec3 w) {
  return 1.0f - dot(cap.axis, w) <= cap.oneMinusCosMax;
}

// --- Spherical rectangles (Urena, Fajardo & King 2013, "An Area-Preserving Parametrization for
// Spherical Rectangles", sections 3-4) ---

struct SphericalRect {
  vec3 o, x, y, z;  // reference point and the local frame (z points away from the rect)
  float x0, x1, y0, y1, z0;
  float b0, b1, k, solidAngle;
};

// The angle between unit vectors a and b.
IBL_FN float unitAngle(vec3 a, vec3 b) {
  return acos(clamp(dot(a, b), -1.0f, 1.0f));
}

// The rectangle of corner s and edges ex, ey seen from p (section 3).
IBL_FN SphericalRect sphericalRect(vec3 p, vec3 s, vec3 ex, vec3 ey) {
  SphericalRect r;
  r.o = p;
  float exl = length(ex), eyl = length(ey);
  r.x = ex / exl;
  r.y = ey / eyl;
  r.z = cross(r.x, r.y);
  vec3 d = s - p;
  r.z0 = dot(d, r.z);
  if (r.z0 > 0.0f) {  // the frame's z must point away from the rectangle
    r.z = -r.z;
    r.z0 = -r.z0;
  }
  r.x0 = dot(d, r.x);
  r.y0 = dot(d, r.y);
  r.x1 = r.x0 + exl;
  r.y1 = r.y0 + eyl;
  vec3 v00 = vec3(r.x0, r.y0, r.z0), v01 = vec3(r.x0, r.y1, r.z0), v10 = vec3(r.x1, r.y0, r.z0),
       v11 = vec3(r.x1, r.y1, r.z0);
  vec3 n0 = normalize(cross(v00, v10)), n1 = normalize(cross(v10, v11)),
       n2 = normalize(cross(v11, v01)), n3 = normalize(cross(v01, v00));
  float g0 = unitAngle(-n0, n1), g1 = unitAngle(-n1, n2), g2 = unitAngle(-n2, n3),
        g3 = unitAngle(-n3, n0);
  r.b0 = n0.z;
  r.b1 = n2.z;
  r.k = 2.0f * kPi - g2 - g3;
  r.solidAngle = g0 + g1 - r.k;
  return r;
}

// The point of the rectangle for xi, uniform in solid angle (section 4).
IBL_FN vec3 sampleSphericalRect(SphericalRect r, vec2 xi) {
  float au = xi.x * r.solidAngle + r.k;
  float fu = (cos(au) * r.b0 - r.b1) / sin(au);
  float cu = (fu >= 0.0f ? 1.0f : -1.0f) / sqrt(fu * fu + r.b0 * r.b0);
  cu = clamp(cu, -0.99999994f, 0.99999994f);
  float xu = -(cu * r.z0) / sqrt(max(0.0f, 1.0f - cu * cu));
  xu = clamp(xu, r.x0, r.x1);
  float d = sqrt(xu * xu + r.z0 * r.z0);
  float h0 = r.y0 / sqrt(d * d + r.y0 * r.y0), h1 = r.y1 / sqrt(d * d + r.y1 * r.y1);
  float hv = h0 + xi.y * (h1 - h0), hv2 = hv * hv;
  float yv = hv2 < 1.0f - 1e-6f ? hv * d / sqrt(1.0f - hv2) : r.y1;
  return r.o + xu * r.x + yv * r.y + r.z0 * r.z;
}

// A rect light seen from p.
IBL_FN SphericalRect rectLightSeenFrom(ShadingLight l, vec3 p) {
  vec3 left = cross(l.up, l.direction);
  vec3 s = l.position - 0.5f * l.width * left - 0.5f * l.height * l.up;
  return sphericalRect(p, s, l.width * left, l.height * l.up);
}

// Area sampling's density per solid angle: d^2 / (A cos), 0 from the back.
IBL_FN float areaSamplingPdf(vec3 w, float distance, vec3 surfaceNormal, float area) {
  float cosLight = -dot(surfaceNormal, w);
  if (!(cosLight > 0.0f)) return 0.0f;
  return distance * distance / (area * cosLight);
}

// A capsule's area (radius, segment length = ShadingLight.width).
IBL_FN float capsuleLightArea(ShadingLight l) {
  return 2.0f * kPi * l.radius * l.width + 4.0f * kPi * l.radius * l.radius;
}

// The outward normal of a capsule light at surface point q.
IBL_FN vec3 capsuleLightNormal(ShadingLight l, vec3 q) {
  vec3 d = q - l.position;
  float along = clamp(dot(d, l.direction), -0.5f * l.width, 0.5f * l.width);
  return normalize(d - along * l.direction);
}

// --- Sampling and densities ---

struct AreaLightSample {
  vec3 direction;  // unit, from the point toward the light
  float distance;  // to the sampled point (kSunDistance: the sun)
  vec3 radiance;   // the luminance arriving along `direction`, no range window
  float pdf;       // per solid angle; 0: the sample carries nothing
};

// A sample of a sun or area light (not punctual) seen from point p, xi uniform in [0, 1)^2.
IBL_FN AreaLightSample sampleAreaLight(ShadingLight l, vec3 p, vec2 xi) {
  AreaLightSample s;
  s.direction = vec3(0.0f, 0.0f, 1.0f);
  s.distance = 0.0f;
  s.radiance = vec3(0.0f);
  s.pdf = 0.0f;
  if (l.type == kLightSun) {
    LightCap cap = sunLightCap(l);
    s.direction = sampleLightCap(cap, xi);
    s.distance = kSunDistance;
    s.radiance = emitterRadiance(l, s.direction);
    s.pdf = lightCapPdf(cap);
  } else if (l.type == kLightSphere) {
    LightCap cap = sphereLightCap(l, p);
    if (!cap.valid) return s;
    s.direction = sampleLightCap(cap, xi);
    s.distance = raySphereDistance(p, s.direction, l.position, l.radius);
    if (s.distance < 0.0f) s.distance = length(l.position - p);  // grazing
    s.radiance = l.color;
    s.pdf = lightCapPdf(cap);
  } else if (l.type == kLightDisk) {
    mat3 frame = tangentFrame(l.direction);
    float rho = l.radius * sqrt(xi.x), phi = 2.0f * kPi * xi.y;
    vec3 q = l.position + frame * vec3(rho * cos(phi), rho * sin(phi), 0.0f);
    vec3 d = q - p;
    s.distance = length(d);
    s.direction = d / s.distance;
    s.pdf = areaSamplingPdf(s.direction, s.distance, l.direction, kPi * l.radius * l.radius);
    if (s.pdf > 0.0f) s.radiance = l.color;
  } else if (l.type == kLightRect) {
    SphericalRect r = rectLightSeenFrom(l, p);
    if (!(r.solidAngle > 1e-9f)) return s;
    vec3 d = sampleSphericalRect(r, xi) - p;
    s.distance = length(d);
    s.direction = d / s.distance;
    s.pdf = 1.0f / r.solidAngle;
    if (dot(p - l.position, l.direction) > 0.0f) s.radiance = l.color;
  } else if (l.type == kLightTube) {
    float area = capsuleLightArea(l);
    float cylinder = 2.0f * kPi * l.radius * l.width / area;
    mat3 frame = tangentFrame(l.direction);
    vec3 q, normal;
    if (xi.x < cylinder) {
      float z = (xi.x / cylinder - 0.5f) * l.width, phi = 2.0f * kPi * xi.y;
      normal = frame * vec3(cos(phi), sin(phi), 0.0f);
      q = l.position + z * l.direction + l.radius * normal;
    } else {
      float u = (xi.x - cylinder) / (1.0f - cylinder);
      float cosTheta = 1.0f - 2.0f * min(u, 1.0f);
      float sinTheta = sqrt(max(0.0f, 1.0f - cosTheta * cosTheta));
      float phi = 2.0f * kPi * xi.y;
      normal = frame * vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
      float end = cosTheta >= 0.0f ? 0.5f * l.width : -0.5f * l.width;
      q = l.position + end * l.direction + l.radius * normal;
    }
    vec3 d = q - p;
    s.distance = length(d);
    s.direction = d / s.distance;
    s.pdf = areaSamplingPdf(s.direction, s.distance, normal, area);
    if (s.pdf > 0.0f) s.radiance = l.color;
  }
  return s;
}

// The density per solid angle with which sampleAreaLight(l, p, .) picks unit direction w (0 if
// it never does, and for punctual lights).
IBL_FN float areaLightPdf(ShadingLight l, vec3 p, vec3 w) {
  if (l.type == kLightSun) {
    LightCap cap = sunLightCap(l);
    return inLightCap(cap, w) ? lightCapPdf(cap) : 0.0f;
  }
  if (l.type == kLightSphere) {
    LightCap cap = sphereLightCap(l, p);
    return cap.valid && inLightCap(cap, w) ? lightCapPdf(cap) : 0.0f;
  }
  if (l.type == kLightDisk) {
    float t = emitterDistance(l, p, w);
    return t < 0.0f ? 0.0f : areaSamplingPdf(w, t, l.direction, kPi * l.radius * l.radius);
  }
  if (l.type == kLightRect) {
    if (emitterDistance(l, p, w) < 0.0f) return 0.0f;
    SphericalRect r = rectLightSeenFrom(l, p);
    return r.solidAngle > 1e-9f ? 1.0f / r.solidAngle : 0.0f;
  }
  if (l.type == kLightTube) {
    float t = emitterDistance(l, p, w);
    if (t < 0.0f) return 0.0f;
    return areaSamplingPdf(w, t, capsuleLightNormal(l, p + t * w), capsuleLightArea(l));
  }
  return 0.0f;
}

// The range window of a light seen from p (1 without a range, and for the sun).
IBL_FN float lightRangeWindow(ShadingLight l, vec3 p) {
  if (l.invSquaredRange <= 0.0f || l.type == kLightSun) return 1.0f;
  vec3 d = l.position - p;
  return smoothDistanceWindow(dot(d, d), l.invSquaredRange);
}

// The irradiance per unit color a surface facing a punctual light receives from it, without an
// IES profile (the callers multiply theirs): I / d^2 with the range window and a spot's cone.
IBL_FN float punctualLightIrradiance(ShadingLight l, vec3 p) {
  vec3 d = l.position - p;
  float d2 = dot(d, d);
  float e = distanceAttenuation(d2, l.invSquaredRange);
  if (l.type == kLightSpot)
    e *= spotAngleAttenuation(dot(l.direction, -d / sqrt(d2)), l.cosInner, l.cosOuter);
  return e;
}

IBL_END

#endif
