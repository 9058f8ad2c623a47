// API: internal (may change without notice; math shared with the shaders)
// Local light probes (Lagarde & de Rousiers 2014, "Moving Frostbite to PBR", section 4.9.3 and
// appendix F; Lagarde & Zanuttini 2012, "Local Image-based Lighting with Parallax-corrected
// Cubemaps"): a cube map captured at a point of the scene is looked up along the direction from
// its capture point to where the reflected ray meets a proxy of the scene (a sphere or an
// oriented box), and weighed by an influence volume that fades out at its border. C++ and GLSL
// (see lang.h): the CPU split sum (src/render/probe.cpp) and the viewer call these.
#ifndef IBL_SHARED_PROBES_H
#define IBL_SHARED_PROBES_H
#include "ibl/shared/lang.h"

IBL_BEGIN

// A sphere or an oriented box in world space.
struct ProbeVolume {
  int shape;          // 0: sphere, 1: box
  vec3 center;        // world
  vec3 halfExtent;    // box: half sizes along its axes; sphere: the radius in x
  mat3 worldToLocal;  // box: rotation from world axes to the box's (its transpose is the inverse)
};

// The distance from p along unit d to where the ray leaves the volume (the far intersection,
// Frostbite appendix F); negative when the ray misses it.
IBL_FN float volumeExitDistance(ProbeVolume v, vec3 p, vec3 d) {
  if (v.shape == 0) {
    vec3 o = p - v.center;
    float b = dot(o, d);
    float c = dot(o, o) - v.halfExtent.x * v.halfExtent.x;
    float disc = b * b - c;
    if (disc < 0.0f) return -1.0f;
    return -b + sqrt(disc);
  }
  vec3 o = v.worldToLocal * (p - v.center);
  vec3 dl = v.worldToLocal * d;
  // Slabs: the far distance is the nearest of the three exits (Williams et al. 2005).
  vec3 safe;
  safe.x = abs(dl.x) > 1e-12f ? dl.x : 1e-12f;
  safe.y = abs(dl.y) > 1e-12f ? dl.y : 1e-12f;
  safe.z = abs(dl.z) > 1e-12f ? dl.z : 1e-12f;
  vec3 inv = vec3(1.0f) / safe;
  vec3 t1 = (-v.halfExtent - o) * inv;
  vec3 t2 = (v.halfExtent - o) * inv;
  vec3 tFar = max(t1, t2);
  vec3 tNear = min(t1, t2);
  float exitT = min(min(tFar.x, tFar.y), tFar.z);
  float entryT = max(max(tNear.x, tNear.y), tNear.z);
  if (exitT < max(entryT, 0.0f)) return -1.0f;
  return exitT;
}

// Frostbite listing in appendix F: the roughness of a lobe whose footprint on the proxy is seen
// from the capture point rather than the shaded point, alpha' = (d_receiver / d_center) alpha,
// clamped to the original and blended back toward it as roughness grows (the estimate holds
// for smooth surfaces only). Perceptual roughness in and out.
IBL_FN float distanceBasedRoughness(float receiverToHit, float centerToHit, float roughness) {
  float scaled = clamp(receiverToHit / max(centerToHit, 1e-6f) * roughness, 0.0f, roughness);
  return mix(scaled, roughness, roughness);
}

// Where a probe's specular map is read for a point, and with which roughness.
struct ParallaxLookup {
  vec3 direction;   // from the capture point (unit)
  float roughness;  // perceptual, for the mip level
};

// The parallax-corrected lookup: the ray from `position` along the (dominant) reflection `r`
// meets the proxy at x; the probe captured x along x - capturePoint. The corrected direction is
// blended back toward r as roughness grows (appendix F: the correction is wrong for wide
// lobes). Without a hit (a point outside the proxy looking away) r itself is used.
IBL_FN ParallaxLookup parallaxCorrectedLookup(ProbeVolume proxy, vec3 capturePoint, vec3 position,
                                              vec3 r, float roughness, bool distanceRoughness) {
  ParallaxLookup look;
  look.direction = r;
  look.roughness = roughness;
  float t = volumeExitDistance(proxy, position, r);
  if (t <= 0.0f) return look;
  vec3 fromCenter = position + t * r - capturePoint;
  float centerToHit = length(fromCenter);
  if (centerToHit <= 1e-6f) return look;
  vec3 corrected = fromCenter / centerToHit;
  look.direction = normalize(mix(corrected, r, roughness));
  if (distanceRoughness) look.roughness = distanceBasedRoughness(t, centerToHit, roughness);
  return look;
}

// 3t^2 - 2t^3: the fade's smooth transition (Frostbite appendix F).
IBL_FN float smoothFade(float t) {
  t = clamp(t, 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// The influence of a probe at p: 1 inside the volume shrunk by `fade`, 0 outside the volume,
// a smooth fade between (Frostbite appendix F: sphere by the distance to the center, box by the
// distance to the inner box).
IBL_FN float influenceWeight(ProbeVolume v, float fade, vec3 p) {
  float f = max(fade, 1e-4f);
  if (v.shape == 0) return smoothFade((v.halfExtent.x - length(p - v.center)) / f);
  vec3 o = abs(v.worldToLocal * (p - v.center));
  if (o.x > v.halfExtent.x || o.y > v.halfExtent.y || o.z > v.halfExtent.z) return 0.0f;
  vec3 inner = max(v.halfExtent - vec3(fade), vec3(0.0f));
  vec3 outside = max(o - inner, vec3(0.0f));
  return smoothFade(1.0f - length(outside) / f);
}

// Frostbite section 4.9.5: probes are composed from the smallest to the largest while the
// coverage is below 1; each adds what its weight has beyond the coverage so far (then coverage
// += share), and the distant environment gets 1 - coverage.
IBL_FN float probeShare(float weight, float coverage) {
  return clamp(weight - coverage, 0.0f, 1.0f);
}

// The coverage after a probe took `share` of a lookup whose capture covers `alpha` of it (the
// capture's coverage filtered like the lookup: 1 where the probe saw the scene, 0 where it saw
// the distant environment). Its color was premultiplied by that alpha; what it leaves uncovered
// goes to the next probe, or to the distant environment seen from the shaded point (Frostbite
// 4.9.5's listing, which weighs a local probe by its alpha).
IBL_FN float coverageAfterProbe(float coverage, float share, float alpha) {
  return min(coverage + share * clamp(alpha, 0.0f, 1.0f), 1.0f);
}

IBL_END

#endif
