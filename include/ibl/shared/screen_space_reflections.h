// API: internal (may change without notice; math shared with the shaders)
// Screen-space reflections: the near reflections no probe holds, traced through the frame's own
// view buffers (Lagarde & de Rousiers 2014, "Moving Frostbite to PBR", section 4.9.4) and
// composed before the probes (section 4.9.5). Stochastic, as Stachowiak 2015 ("Stochastic
// Screen-Space Reflections"): each pixel reflects a few rays whose half vectors are drawn from
// its GGX lobe, each ray is marched across the screen (a digital differential analyzer over the
// depth, McGuire & Mara 2014, "Efficient GPU Screen-Space Ray Tracing", with a perspective-correct
// depth, the buffer's depth taken from each texel's plane, and a bisection at the crossing), and a
// hit takes the radiance the lit frame has there. Rays that leave the screen, run out of steps, or
// meet the back of a surface miss, and a pixel keeps what share of its lobe missed for the probes.
// C++ and GLSL (see lang.h): the CPU split sum (src/render/screen_space_reflections.cpp) and the
// viewer's pass (shaders/view/ssr.frag).
#ifndef IBL_SHARED_SCREEN_SPACE_REFLECTIONS_H
#define IBL_SHARED_SCREEN_SPACE_REFLECTIONS_H
#include "ibl/shared/ambient_occlusion.h"
#include "ibl/shared/brdf.h"
#include "ibl/shared/lang.h"
#include "ibl/shared/sampling.h"
#include "ibl/shared/split_sum.h"

IBL_BEGIN

struct ReflectionParameters {
  float maxDistance;  // world units a ray travels at most
  float thickness;  // the depth a surface is taken to have behind the buffer, a share of its depth
  float stride;     // pixels per step (more where the ray would need more than maxSteps)
  int maxSteps;     // steps per ray
  int rays;         // rays per pixel
  float fadeStart;  // perceptual roughness where the reflection starts to fade to the probes
  float fadeEnd;    // ... and where it is gone
  float edgeFade;   // the share of the screen's smaller side over which hits near a border fade
};

#ifdef __cplusplus
// The frame's buffers at the pixel centers, row-major: view-space positions (z <= 0: no
// surface) and unit normals, and the lit frame's radiance.
struct ReflectionBuffers {
  const vec3* positions;
  const vec3* normals;
  const vec3* radiance;
  int width, height;
  const float* roughness;  // perceptual (the resolve reads it)
  const vec4* traced;      // screenSpaceReflection per pixel (the resolve reads it)
};
inline std::size_t reflectionTexel(const ReflectionBuffers& b, ivec2 t) {
  return static_cast<std::size_t>(t.y) * static_cast<std::size_t>(b.width) +
         static_cast<std::size_t>(t.x);
}
inline vec3 ssrViewPosition(const ReflectionBuffers& b, ivec2 t) {
  return b.positions[reflectionTexel(b, t)];
}
inline vec3 ssrViewNormal(const ReflectionBuffers& b, ivec2 t) {
  return b.normals[reflectionTexel(b, t)];
}
inline vec3 ssrRadiance(const ReflectionBuffers& b, ivec2 t) {
  return b.radiance[reflectionTexel(b, t)];
}
inline float ssrRoughness(const ReflectionBuffers& b, ivec2 t) {
  return b.roughness[reflectionTexel(b, t)];
}
inline vec4 ssrTraced(const ReflectionBuffers& b, ivec2 t) {
  return b.traced[reflectionTexel(b, t)];
}
#define IBL_SSR_BUFFER const ReflectionBuffers &buffer,
#define IBL_SSR_ARG buffer,
#else
// Defined by the includer: the frame's view-space position, unit view-space normal and lit
// radiance at texel t; for the resolve, the perceptual roughness and the traced reflection.
vec3 ssrViewPosition(ivec2 t);
vec3 ssrViewNormal(ivec2 t);
vec3 ssrRadiance(ivec2 t);
float ssrRoughness(ivec2 t);
vec4 ssrTraced(ivec2 t);
#define IBL_SSR_BUFFER
#define IBL_SSR_ARG
#endif

// The texel under framebuffer point q, kept on the screen.
IBL_FN ivec2 reflectionTexelAt(ScreenProjection s, vec2 q) {
  vec2 t = clamp(floor(q), vec2(0.0f), s.size - vec2(1.0f));
  return ivec2(int(t.x), int(t.y));
}

// The depth of the buffer's surface under framebuffer point q: the plane of the texel there (its
// position and normal) met by the view ray through q, so that a plane's depth is exact between
// texel centers and a ray that leaves a surface does not meet it again; the texel's own depth
// where its plane is seen nearly edge-on. 0: no surface.
IBL_FN float bufferDepthAt(IBL_SSR_BUFFER ScreenProjection s, vec2 q) {
  ivec2 t = reflectionTexelAt(s, q);
  vec3 p = ssrViewPosition(IBL_SSR_ARG t);
  if (p.z <= 0.0f) return 0.0f;
  vec3 n = ssrViewNormal(IBL_SSR_ARG t);
  vec2 xy = vec2(2.0f * q.x / s.size.x - 1.0f, 1.0f - 2.0f * q.y / s.size.y) * s.scale;
  if (s.perspective > 0.5f) {
    vec3 d = vec3(xy.x, xy.y, 1.0f);
    float facing = dot(n, d);
    if (abs(facing) < 0.1f * length(d)) return p.z;
    return max(dot(n, p) / facing, 1e-6f);
  }
  if (abs(n.z) < 0.1f) return p.z;
  return (dot(n, p) - n.x * xy.x - n.y * xy.y) / n.z;
}

// The view depth along a ray whose ends project to screen points with inverse depths k0, k1
// (perspective; 1 for orthographic) and depths z0, z1, at screen parameter t: depth is not linear
// on the screen, its inverse is (McGuire & Mara 2014, section 2.1).
IBL_FN float screenRayDepth(float z0, float z1, float k0, float k1, float t) {
  return mix(z0 * k0, z1 * k1, t) / mix(k0, k1, t);
}

// How far from the screen's border a hit at q is, faded over `edgeFade` of the smaller side.
IBL_FN float screenEdgeFade(ScreenProjection s, vec2 q, float edgeFade) {
  float border = min(min(q.x, s.size.x - q.x), min(q.y, s.size.y - q.y));
  return clamp(border / max(edgeFade * min(s.size.x, s.size.y), 1e-6f), 0.0f, 1.0f);
}

// A hit on a surface seen nearly edge-on from the ray fades out, and one on a surface's back
// (the buffer holds the front of something else) is none: over the last ~6 degrees.
IBL_FN float backFaceFade(vec3 hitNormal, vec3 d) {
  return clamp(-10.0f * dot(hitNormal, d), 0.0f, 1.0f);
}

struct ScreenRayHit {
  vec2 pixel;        // framebuffer point of the hit
  float confidence;  // 0: a miss; else the product of the fades
};

// Marches the view-space ray from p along unit d across the screen from jittered start
// `jitter` in [0, 1) of a step. A step hits when the ray's depth over it spans the buffer's depth
// there, within the surface's thickness; the crossing is then found by bisection.
IBL_FN ScreenRayHit traceScreenRay(IBL_SSR_BUFFER ScreenProjection s, vec3 p, vec3 d, float jitter,
                                   ReflectionParameters r) {
  ScreenRayHit hit;
  hit.pixel = vec2(0.0f);
  hit.confidence = 0.0f;
  bool perspective = s.perspective > 0.5f;
  // Keep the ray in front of the camera.
  float len = r.maxDistance;
  float nearZ = 0.01f * p.z;
  if (perspective && d.z < 0.0f) len = min(len, (nearZ - p.z) / d.z);
  vec3 e = p + len * d;
  vec2 h0 = projectToPixel(s, p);
  vec2 h1 = projectToPixel(s, e);
  float k0 = perspective ? 1.0f / p.z : 1.0f;
  float k1 = perspective ? 1.0f / e.z : 1.0f;
  // Clip the march to the screen.
  vec2 delta = h1 - h0;
  float tEnd = 1.0f;
  if (delta.x > 0.0f) tEnd = min(tEnd, (s.size.x - h0.x) / delta.x);
  if (delta.x < 0.0f) tEnd = min(tEnd, -h0.x / delta.x);
  if (delta.y > 0.0f) tEnd = min(tEnd, (s.size.y - h0.y) / delta.y);
  if (delta.y < 0.0f) tEnd = min(tEnd, -h0.y / delta.y);
  float pixels = max(abs(delta.x), abs(delta.y)) * tEnd;
  if (pixels < 1.0f) return hit;
  float steps = min(float(r.maxSteps), ceil(pixels / r.stride));
  float dt = tEnd / steps;
  float prevT = 0.0f;
  float prevZ = p.z;
  for (int i = 0; i < r.maxSteps; ++i) {
    if (float(i) >= steps) break;
    float t = (float(i) + jitter) * dt + 0.5f * dt;
    t = min(t, tEnd);
    float z = screenRayDepth(p.z, e.z, k0, k1, t);
    float scene = bufferDepthAt(IBL_SSR_ARG s, mix(h0, h1, t));
    if (scene > 0.0f && max(prevZ, z) >= scene && min(prevZ, z) <= scene * (1.0f + r.thickness)) {
      // Bisection: lo in front of the buffer, hi behind it.
      float lo = prevT, hi = t;
      for (int j = 0; j < 6; ++j) {
        float mid = 0.5f * (lo + hi);
        float m = bufferDepthAt(IBL_SSR_ARG s, mix(h0, h1, mid));
        if (m > 0.0f && screenRayDepth(p.z, e.z, k0, k1, mid) >= m)
          hi = mid;
        else
          lo = mid;
      }
      hit.pixel = mix(h0, h1, hi);
      ivec2 texel = reflectionTexelAt(s, hit.pixel);
      hit.confidence = screenEdgeFade(s, hit.pixel, r.edgeFade) *
                       backFaceFade(ssrViewNormal(IBL_SSR_ARG texel), d);
      return hit;
    }
    prevT = t;
    prevZ = z;
  }
  return hit;
}

// 1 up to fadeStart, 0 from fadeEnd: rough lobes need more rays than a frame affords, and the
// probes' prefiltered maps hold them well.
IBL_FN float roughnessFade(float roughness, ReflectionParameters r) {
  return 1.0f - clamp((roughness - r.fadeStart) / max(r.fadeEnd - r.fadeStart, 1e-6f), 0.0f, 1.0f);
}

// The reflection at a pixel of perceptual roughness `roughness`: rgb is the lobe's radiance
// from the hits, weighted by n.l as the prefiltered maps are (Karis 2013) and premultiplied by
// alpha, the share of the lobe the screen holds (times the roughness fade). Half vectors are
// drawn from D(h) (n.h) by a rank-1 lattice offset per pixel by interleaved gradient noise.
IBL_FN vec4 screenSpaceReflection(IBL_SSR_BUFFER ScreenProjection s, ivec2 pixel, float roughness,
                                  ReflectionParameters r) {
  vec3 p = ssrViewPosition(IBL_SSR_ARG pixel);
  float fade = roughnessFade(roughness, r);
  if (p.z <= 0.0f || fade <= 0.0f) return vec4(0.0f);
  vec3 n = ssrViewNormal(IBL_SSR_ARG pixel);
  vec3 v = viewDirectionAt(s, p);
  // Off the surface by half a pixel's footprint, against rounding.
  vec3 origin = p + n * (0.5f / pixelsPerUnit(s, p.z));
  mat3 frame = tangentFrame(n);
  float alpha = alphaFromRoughness(roughness);
  vec2 center = vec2(float(pixel.x), float(pixel.y)) + vec2(0.5f);
  vec2 noise =
      vec2(interleavedGradientNoise(center), interleavedGradientNoise(center + vec2(47.0f, 17.0f)));
  vec3 sum = vec3(0.0f);
  float covered = 0.0f, weights = 0.0f;
  for (int k = 0; k < r.rays; ++k) {
    vec2 xi = noise + float(k) * vec2(0.7548776662f, 0.5698402910f);  // the R2 sequence
    xi = xi - floor(xi);
    vec3 h = frame * sampleGgxHalfVector(xi, alpha);
    vec3 l = 2.0f * dot(v, h) * h - v;
    float NoL = dot(n, l);
    if (NoL <= 0.0f) continue;
    float jitter = xi.x + 0.6180339887f * xi.y;
    ScreenRayHit hit = traceScreenRay(IBL_SSR_ARG s, origin, l, jitter - floor(jitter), r);
    weights += NoL;
    if (hit.confidence > 0.0f) {
      float w = NoL * hit.confidence;
      sum += w * ssrRadiance(IBL_SSR_ARG reflectionTexelAt(s, hit.pixel));
      covered += w;
    }
  }
  if (weights <= 0.0f) return vec4(0.0f);
  return vec4(sum / weights, covered / weights) * fade;
}

// Lobes at least this rough share their neighbors' rays in the resolve; smoother ones keep
// their own (a neighbor's hit lies where a mirror does not look).
const float kReflectionReuseRoughness = 0.2f;

// The resolve of Stachowiak 2015, reduced to what the traced results hold: a glossy pixel takes
// its 3 x 3 neighbors' reflections besides its own, where the neighbor's surface continues its
// own (within the thickness of its plane), each weighted by how likely its own lobe reflects
// along the neighbor's: GGX's D at the neighbor's normal relative to D's peak. Every pixel then
// averages nine times the rays it traced, at the cost of a pixel's worth of blur.
IBL_FN vec4 resolveScreenReflection(IBL_SSR_BUFFER ScreenProjection s, ivec2 pixel,
                                    ReflectionParameters r) {
  vec4 own = ssrTraced(IBL_SSR_ARG pixel);
  float roughness = ssrRoughness(IBL_SSR_ARG pixel);
  vec3 p = ssrViewPosition(IBL_SSR_ARG pixel);
  if (p.z <= 0.0f || roughness < kReflectionReuseRoughness || roughnessFade(roughness, r) <= 0.0f)
    return own;
  vec3 n = ssrViewNormal(IBL_SSR_ARG pixel);
  float alpha = alphaFromRoughness(roughness);
  float a2 = alpha * alpha;
  vec4 sum = own;
  float weights = 1.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = ivec2(pixel.x + dx, pixel.y + dy);
      if ((dx == 0 && dy == 0) || q.x < 0 || q.y < 0 || float(q.x) >= s.size.x ||
          float(q.y) >= s.size.y)
        continue;
      vec3 pq = ssrViewPosition(IBL_SSR_ARG q);
      if (pq.z <= 0.0f || abs(dot(n, pq - p)) > r.thickness * p.z) continue;
      float c = dot(n, ssrViewNormal(IBL_SSR_ARG q));
      if (c <= 0.0f) continue;
      float d = c * c * (a2 - 1.0f) + 1.0f;
      float w = a2 * a2 / (d * d);
      sum += w * ssrTraced(IBL_SSR_ARG q);
      weights += w;
    }
  return sum / weights;
}

// Lagarde & de Rousiers 2014, 4.9.5: the screen's reflection first, then the probes' composition
// (local probes from the smallest, then the distant one) for the share it leaves. The specular
// occlusion of the ambient occlusion darkens the probes' part only: a traced reflection has its
// own visibility.
IBL_FN vec3 composeScreenReflection(vec4 reflection, vec3 probes, float probeOcclusion) {
  return vec3(reflection.x, reflection.y, reflection.z) +
         (1.0f - reflection.w) * probeOcclusion * probes;
}

// What specular occlusion (split_sum.h) the probes' share gets beside a screen-space reflection:
// the ambient occlusion's, when the switches ask for it.
IBL_FN float probeSpecularOcclusion(SplitSumSwitches s, float NoV, SplitSumMaterial m) {
  if (!s.specularOcclusion || m.occlusion >= 1.0f) return 1.0f;
  return specularOcclusion(NoV, m.occlusion, alphaFromRoughness(m.roughness));
}

IBL_END

#endif
