// API: internal (may change without notice; math shared with the shaders)
// Screen-space ambient occlusion: ground-truth ambient occlusion (GTAO; Jimenez, Wu, Pesce &
// Jarabo 2016, "Practical Real-Time Strategies for Accurate Indirect Occlusion"), from a buffer
// of view-space positions. C++ and GLSL (see lang.h): the CPU's split sum
// (src/render/ambient_occlusion.cpp) and the viewer's full-screen pass (shaders/view/gtao.frag)
// both call groundTruthAmbientOcclusion.
//
// View space here is the camera's frame: x right, y up, z the distance along the view (> 0 in
// front of the camera); a position with z <= 0 marks a pixel where no surface is. Each pixel's
// hemisphere is cut into `slices` planes that contain the view vector; along each, the horizon
// on both sides is the steepest of `steps` samples of the buffer within `radius`, and the
// cosine-weighted visible arc between the horizons is integrated in closed form (the paper's
// inner integral), its mean direction too (the bent normal). Its multiple-bounce fit is in
// split_sum.h, where the occlusion meets the material.
#ifndef IBL_SHARED_AMBIENT_OCCLUSION_H
#define IBL_SHARED_AMBIENT_OCCLUSION_H
#include "ibl/shared/lang.h"

IBL_BEGIN

// How view space maps to pixels: x_ndc = x / (scale.x w), y_ndc = y / (scale.y w) with w = z
// (perspective) or 1 (orthographic); pixel (0, 0) is the top-left corner.
struct ScreenProjection {
  vec2 size;          // width, height in pixels
  vec2 scale;         // the view's half extent at unit distance (perspective) or in world units
  float perspective;  // 1 perspective, 0 orthographic
};

IBL_FN vec2 projectToPixel(ScreenProjection s, vec3 position) {
  float w = s.perspective > 0.5f ? position.z : 1.0f;
  vec2 ndc = vec2(position.x, position.y) / (s.scale * w);
  return vec2((ndc.x + 1.0f) * 0.5f * s.size.x, (1.0f - ndc.y) * 0.5f * s.size.y);
}

// The unit direction from a view-space position toward the camera.
IBL_FN vec3 viewDirectionAt(ScreenProjection s, vec3 position) {
  return s.perspective > 0.5f ? normalize(-position) : vec3(0.0f, 0.0f, -1.0f);
}

// Pixels per world unit across the view at distance z.
IBL_FN float pixelsPerUnit(ScreenProjection s, float z) {
  return 0.5f * s.size.y / (s.scale.y * (s.perspective > 0.5f ? z : 1.0f));
}

// The normal the view buffers hold for a surface point: its shading normal n on the side of the
// surface the camera sees, that side decided by the geometric normal g (the triangle's plane,
// either orientation), v the unit direction toward the camera. Shading flips n whenever it faces
// away from the camera (a double-sided surface seen from behind), but an interpolated or
// normal-mapped n also points past the horizon where its triangle faces the camera: along a
// smooth mesh's outline, where the vertex normals are perpendicular to the view and the pixel
// center's surface, between them, is not. Flipped there, n points into the object, whose own
// nearer surface then stands above that tangent plane and hides nearly all of it (a black pixel
// on the outline, issue 47). Here n is turned to agree with the side of g the camera sees, then,
// if it still faces away, bent to just in front of the horizon. Either sign of n gives the same.
IBL_FN vec3 viewBufferNormal(vec3 n, vec3 g, vec3 v) {
  if (dot(g, n) < 0.0f) g = -g;
  if (dot(g, v) < 0.0f) n = -n;
  float facing = dot(n, v);
  const float kGrazing = 1e-3f;
  return facing < kGrazing ? normalize(n + (kGrazing - facing) * v) : n;
}

struct AmbientOcclusionParameters {
  float radius;   // world units: occluders farther than this hide nothing
  float falloff;  // the outer share of the radius over which an occluder's weight fades to 0
  int slices;     // planes per pixel
  int steps;      // samples per side of each plane
};

struct AmbientOcclusion {
  float visibility;  // cosine-weighted share of the hemisphere that is open, 0..1
  vec3 bentNormal;   // the open directions' cosine-weighted mean, unit, view space
};

// Interleaved gradient noise (Jimenez 2014, "Next Generation Post Processing in Call of Duty:
// Advanced Warfare"): a value in [0, 1) per pixel whose neighbors differ as much as possible.
IBL_FN float interleavedGradientNoise(vec2 pixel) {
  float f = 0.06711056f * pixel.x + 0.00583715f * pixel.y;
  f = f - floor(f);
  f = 52.9829189f * f;
  return f - floor(f);
}

// The cosine-weighted visible measure of one side of a slice, from the view vector (angle 0) to
// the horizon at angle h (the side's sign included), for a normal at angle n in the slice:
// the integral of cos(t - n) |sin t| dt, one of the two terms of the paper's closed form.
IBL_FN float sliceArcVisibility(float h, float n) {
  return 0.25f * (-cos(2.0f * h - n) + cos(n) + 2.0f * h * sin(n));
}

// The cosine-weighted mean direction of the arc from 0 to h >= 0 on a slice's positive side, as
// (its component along the view vector, along the slice's in-plane direction): integrals of
// cos t cos(t - n) sin t and sin t cos(t - n) sin t over [0, h]. The negative side is the
// mirror: (x, -y) of sliceArcMoments(-h, -n).
IBL_FN vec2 sliceArcMoments(float h, float n) {
  float c = cos(h), s = sin(h);
  float along = cos(n) * (1.0f - c * c * c) / 3.0f + sin(n) * s * s * s / 3.0f;
  float across = cos(n) * s * s * s / 3.0f + sin(n) * (2.0f / 3.0f - c + c * c * c / 3.0f);
  return vec2(along, across);
}

// The weight of an occluder at distance d: 1 within (1 - falloff) radius, fading linearly to 0
// at the radius.
IBL_FN float occluderWeight(float d, AmbientOcclusionParameters a) {
  float width = max(a.falloff * a.radius, 1e-6f * a.radius);
  return clamp((a.radius - d) / width, 0.0f, 1.0f);
}

#ifdef __cplusplus
struct ViewPositions {
  const vec3* positions;  // row-major, width x height
  int width, height;
};
inline vec3 aoViewPosition(const ViewPositions& buffer, ivec2 t) {
  return buffer.positions[static_cast<std::size_t>(t.y) * static_cast<std::size_t>(buffer.width) +
                          static_cast<std::size_t>(t.x)];
}
#define IBL_AO_BUFFER const ViewPositions &buffer,
#define IBL_AO_ARG buffer,
#else
// Defined by the includer: the view-space position at texel t of the frame's buffer.
vec3 aoViewPosition(ivec2 t);
#define IBL_AO_BUFFER
#define IBL_AO_ARG
#endif

// The view-space position at framebuffer point q, bilinear between the four nearest texels
// (points on a plane stay on it, so that a plane's horizon is its own, wherever the sample
// falls between texel centers); no surface (z = 0) where any of the four has none. (The nearest
// texel there is another direction's point: past an outline, the outline's next texel, taken
// for an occluder in the slice, hid up to 7 % of a convex object's outline pixels' hemisphere.)
IBL_FN vec3 aoPositionAt(IBL_AO_BUFFER ScreenProjection s, vec2 q) {
  vec2 t = q - vec2(0.5f);
  vec2 lo = floor(t);
  vec2 f = t - lo;
  ivec2 a = ivec2(int(max(lo.x, 0.0f)), int(max(lo.y, 0.0f)));
  ivec2 b = ivec2(int(min(lo.x + 1.0f, s.size.x - 1.0f)), int(min(lo.y + 1.0f, s.size.y - 1.0f)));
  vec3 p00 = aoViewPosition(IBL_AO_ARG a);
  vec3 p10 = aoViewPosition(IBL_AO_ARG ivec2(b.x, a.y));
  vec3 p01 = aoViewPosition(IBL_AO_ARG ivec2(a.x, b.y));
  vec3 p11 = aoViewPosition(IBL_AO_ARG b);
  if (min(min(p00.z, p10.z), min(p01.z, p11.z)) <= 0.0f) return vec3(0.0f);
  return mix(mix(p00, p10, f.x), mix(p01, p11, f.x), f.y);
}

// The highest horizon (the largest cosine with the view vector v) among the samples from pixel
// `center` along `direction` (pixels), starting from `lowest`: the horizon of the point's own
// tangent plane on that side.
IBL_FN float sliceHorizonCosine(IBL_AO_BUFFER ScreenProjection s, vec2 center, vec2 direction,
                                vec3 p, vec3 v, float radiusPixels, float jitter, float lowest,
                                AmbientOcclusionParameters a) {
  float best = lowest;
  for (int j = 0; j < a.steps; ++j) {
    // Squared spacing: more samples near the point, where contact occlusion is.
    float t = (float(j) + jitter) / float(a.steps);
    vec2 q = center + direction * (1.0f + t * t * (radiusPixels - 1.0f));
    if (q.x < 0.0f || q.y < 0.0f || q.x >= s.size.x || q.y >= s.size.y) break;
    vec3 o = aoPositionAt(IBL_AO_ARG s, q);
    if (o.z <= 0.0f) continue;
    vec3 d = o - p;
    float dist = length(d);
    if (dist <= 0.0f) continue;
    best = max(best, mix(lowest, dot(d, v) / dist, occluderWeight(dist, a)));
  }
  return best;
}

// GTAO at pixel `pixel` whose unit view-space normal is `normal`.
IBL_FN AmbientOcclusion groundTruthAmbientOcclusion(IBL_AO_BUFFER ScreenProjection s, ivec2 pixel,
                                                    vec3 normal, AmbientOcclusionParameters a) {
  AmbientOcclusion result;
  result.visibility = 1.0f;
  result.bentNormal = normal;
  vec3 p = aoViewPosition(IBL_AO_ARG pixel);
  float radiusPixels = a.radius * pixelsPerUnit(s, p.z);
  if (p.z <= 0.0f || radiusPixels < 1.0f || a.slices < 1 || a.steps < 1) return result;
  vec3 v = viewDirectionAt(s, p);
  vec2 center = vec2(pixel) + vec2(0.5f);
  float rotation = interleavedGradientNoise(vec2(pixel));
  float jitter = interleavedGradientNoise(vec2(pixel) + vec2(19.0f, 47.0f));
  float visibility = 0.0f;
  vec3 bent = vec3(0.0f);
  for (int i = 0; i < a.slices; ++i) {
    float phi = (float(i) + rotation) * kPi / float(a.slices);
    vec2 direction = vec2(cos(phi), sin(phi));  // in pixels, y down
    vec3 along = vec3(direction.x, -direction.y, 0.0f);
    vec3 ortho = normalize(along - dot(along, v) * v);  // the slice's in-plane axis
    vec3 axis = cross(ortho, v);                        // the slice plane's normal
    vec3 projected = normal - axis * dot(normal, axis);
    float projectedLength = length(projected);
    if (projectedLength < 1e-6f) continue;
    float cosN = clamp(dot(projected, v) / projectedLength, -1.0f, 1.0f);
    float n = (dot(projected, ortho) < 0.0f ? -1.0f : 1.0f) * acos(cosN);
    // Horizons as cosines with v, from the tangent plane's (cos(n +- pi/2)) up.
    float positive =
        sliceHorizonCosine(IBL_AO_ARG s, center, direction, p, v, radiusPixels, jitter, -sin(n), a);
    float negative =
        sliceHorizonCosine(IBL_AO_ARG s, center, -direction, p, v, radiusPixels, jitter, sin(n), a);
    float h1 = n + min(acos(clamp(positive, -1.0f, 1.0f)) - n, 0.5f * kPi);
    float h0 = n + max(-acos(clamp(negative, -1.0f, 1.0f)) - n, -0.5f * kPi);
    visibility += projectedLength * (sliceArcVisibility(h0, n) + sliceArcVisibility(h1, n));
    vec2 plus = sliceArcMoments(max(h1, 0.0f), n);
    vec2 minus = sliceArcMoments(max(-h0, 0.0f), -n);
    bent += projectedLength * (v * (plus.x + minus.x) + ortho * (plus.y - minus.y));
  }
  result.visibility = clamp(visibility / float(a.slices), 0.0f, 1.0f);
  if (length(bent) > 0.0f) result.bentNormal = normalize(bent);
  return result;
}

IBL_END

#endif
