// API: internal (may change without notice; math shared with the shaders)
// Shadow maps of the analytic lights, read the same way by the CPU split sum and the viewer:
// the light-space projection of each map layer, the choice of a cascade or a cube face, the
// bias, and the percentage-closer soft shadow filter (Fernando 2005, "Percentage-Closer Soft
// Shadows") whose penumbra follows the light's size. C++ and GLSL (see lang.h).
//
// A light's shadow is one or more layers of n x n texels, each storing the depth of the first
// surface along its texel's ray, normalized as (z - near) / (far - near) with z the distance
// along the layer's forward axis (1: nothing). Layers are perspective (spot lights; the six
// faces of a cube around point, sphere, tube, disk and rect lights) or orthographic (the sun's
// cascades, fitted to slices of the view). Where the scene has surfaces that transmit
// (KHR_materials_transmission), each texel also holds a filter: the product of what the
// transmissive surfaces in front of its opaque depth let through (shadowMapCrossing in
// split_sum.h), and the stored depth of the first of them; the depth skips them. What the maps
// hold is read through accessors that each language defines: shadowLayerAt(i),
// shadowDepthTexel(layer, texel) and shadowFilterTexel(layer, texel); in C++ they take the maps
// as a first argument (IBL_SHADOW_MAPS / IBL_SHADOW_ARG below), in GLSL the shader defines them
// over its storage buffers before including this header.
#ifndef IBL_SHARED_SHADOWS_H
#define IBL_SHARED_SHADOWS_H
#include "ibl/shared/cube.h"
#include "ibl/shared/lang.h"

IBL_BEGIN

// ShadowCaster.kind.
const int kShadowNone = 0;
const int kShadowSingle = 1;    // one perspective layer (a spot's cone)
const int kShadowCube = 2;      // six perspective layers in the cube's face order (cube.h)
const int kShadowCascades = 3;  // orthographic layers over consecutive slices of the view depth

// The filter: taps of the blocker search and of the percentage-closer filter, and its smallest
// radius (hides the texels of punctual lights' hard shadows), in texels.
const int kShadowTaps = 16;
const float kShadowMinFilterTexels = 1.5f;
// The bias, in texels' world size at the receiver: along the normal (normal offset), and along
// the light's depth a constant plus a slope-scaled part (times tan of the angle between the
// normal and the light, at most kShadowMaxSlope), on top of the receiver plane the filter
// follows.
const float kShadowNormalOffsetTexels = 1.0f;
const float kShadowDepthBiasTexels = 1.0f;
const float kShadowSlopeBiasTexels = 1.0f;
const float kShadowMaxSlope = 10.0f;

// One layer: its light space (origin, orthonormal axes; z along `forward`) and projection.
struct ShadowLayer {
  vec3 origin;      // perspective: the eye; orthographic: the center of the near plane
  vec3 right;       // the map's x (texel column) grows along it
  vec3 up;          // the map's y (texel row) grows along it
  vec3 forward;     // depth
  int perspective;  // 1 perspective, 0 orthographic
  float scale;      // perspective: tan of the half field of view; orthographic: the half width
  float near;       // the depth range the map stores (world units along forward)
  float far;
};

// One light's shadow: which layers, how to choose among them, and the light's size.
struct ShadowCaster {
  int kind;  // kShadowNone ...
  int firstLayer;
  int layerCount;
  // The penumbra's source: the light's radius in world units (local lights), tan of the sun's
  // angular radius (the sun); 0: a punctual light (hard shadows, filtered over the minimum).
  float size;
  vec3 lightPosition;  // cube and single layers: where the light is
  vec3 viewOrigin;     // cascades: the camera's position and unit forward axis
  vec3 viewForward;
  vec4 splits;  // cascades: the far end of each slice's view depth (unused entries: 0)
};

// The filter's largest radius in texels of a map of mapSize texels: 5 % of its width (at least
// 24 texels), so that a penumbra covers as much of the scene at any map size.
IBL_FN float shadowMaxFilterTexels(float mapSize) {
  return max(24.0f, 0.05f * mapSize);
}

// Where a point falls in a layer: its continuous texel coordinates ((0, 0) the corner of texel
// (0, 0); texel centers at + 0.5), its depth along forward, the world size of a texel there.
struct ShadowProjection {
  vec2 texel;
  float depth;
  float texelSize;
};

IBL_FN ShadowProjection shadowProject(ShadowLayer l, vec3 p, float mapSize) {
  vec3 q = p - l.origin;
  float z = dot(q, l.forward);
  float extent = l.perspective != 0 ? max(z, 1e-6f) * l.scale : l.scale;  // half width at z
  ShadowProjection s;
  s.texel = (vec2(dot(q, l.right), dot(q, l.up)) / extent * 0.5f + vec2(0.5f)) * mapSize;
  s.depth = z;
  s.texelSize = 2.0f * extent / mapSize;
  return s;
}

// The ray of texel coordinates t (continuous, as shadowProject's): for a perspective layer from
// the eye with a direction whose forward component is 1 (so the distance along it is the
// depth); for an orthographic one from the near plane along forward.
IBL_FN vec3 shadowRayDirection(ShadowLayer l, vec2 t, float mapSize) {
  if (l.perspective == 0) return l.forward;
  vec2 uv = (t / mapSize * 2.0f - vec2(1.0f)) * l.scale;
  return l.forward + uv.x * l.right + uv.y * l.up;
}
IBL_FN vec3 shadowRayOrigin(ShadowLayer l, vec2 t, float mapSize) {
  if (l.perspective != 0) return l.origin;
  vec2 xy = (t / mapSize * 2.0f - vec2(1.0f)) * l.scale;
  return l.origin + xy.x * l.right + xy.y * l.up;
}

// The depth a map stores for depth z, and back.
IBL_FN float shadowStoredDepth(ShadowLayer l, float z) {
  return clamp((z - l.near) / (l.far - l.near), 0.0f, 1.0f);
}
IBL_FN float shadowWorldDepth(ShadowLayer l, float stored) {
  return l.near + stored * (l.far - l.near);
}

// Where the rasterizer puts p when it draws a layer as a map of texels (Vulkan's clip space,
// row 0 at y = -1): x / w and y / w cover [-1, 1] across the map exactly as shadowProject's
// texel coordinates cover [0, mapSize], so that a texel's center samples the surface its ray
// meets. Clip z keeps what lies in front of the layer (perspective: from 1e-6 x far to 2 x far,
// so that a surface nearer than the layer's near depth stores 0, as the CPU's texel ray finds
// it; orthographic: from its origin's plane to 2 x far); the depth a texel stores is written by
// the fragment shader (shadowStoredDepth of the surface's own depth).
IBL_FN vec4 shadowClipPosition(ShadowLayer l, vec3 p) {
  vec3 q = p - l.origin;
  float z = dot(q, l.forward);
  vec2 xy = vec2(dot(q, l.right), dot(q, l.up)) / l.scale;
  float zFar = 2.0f * l.far;
  if (l.perspective == 0) return vec4(xy, z / zFar, 1.0f);
  float zNear = 1e-6f * l.far;
  return vec4(xy, zFar * (z - zNear) / (zFar - zNear), z);
}

// The depth at texel coordinates t of the plane through p with normal n (the receiver plane:
// each filter tap compares against the receiver's own depth there, so that a wide filter on a
// surface tilted to the light does not shadow itself; Isidoro 2006). Limited to `limit` from
// the depth at p, for planes seen edge-on.
IBL_FN float receiverPlaneDepth(ShadowLayer l, vec3 p, vec3 n, vec2 t, float mapSize, float depth,
                                float limit) {
  vec3 o = shadowRayOrigin(l, t, mapSize);
  vec3 d = shadowRayDirection(l, t, mapSize);
  float nd = dot(n, d);
  if (abs(nd) < 1e-6f) return depth;
  float z = dot(n, p - o) / nd * dot(d, l.forward);
  return clamp(z, depth - limit, depth + limit);
}

// The cascade whose slice holds a point at `viewDepth` along the camera's forward axis, or -1
// beyond the last.
IBL_FN int shadowCascadeIndex(float viewDepth, vec4 splits, int count) {
  for (int i = 0; i < count; ++i) {
    float end = i == 0 ? splits.x : (i == 1 ? splits.y : (i == 2 ? splits.z : splits.w));
    if (viewDepth <= end) return i;
  }
  return -1;
}

// Tap i of kShadowTaps on the unit disk: a Vogel spiral (golden-angle steps, radii sqrt of the
// index), evenly spread for any count.
IBL_FN vec2 shadowDiskTap(int i) {
  float r = sqrt((float(i) + 0.5f) / float(kShadowTaps));
  float a = float(i) * 2.39996323f;
  return r * vec2(cos(a), sin(a));
}

#ifdef __cplusplus
// The maps as the CPU holds them (render/shadows.hpp owns the storage).
struct ShadowMapView {
  int size = 0;                         // texels per side of every layer
  const float* depths = nullptr;        // layer after layer, rows of `size` texels
  const ShadowLayer* layers = nullptr;  // the layers' records
  const vec4* filters = nullptr;        // as the depths; null: nothing transmits
};
inline ShadowLayer shadowLayerAt(const ShadowMapView& maps, int i) {
  return maps.layers[i];
}
inline float shadowDepthTexel(const ShadowMapView& maps, int layer, ivec2 t) {
  const int n = maps.size;
  const int x = t.x < 0 ? 0 : (t.x >= n ? n - 1 : t.x);
  const int y = t.y < 0 ? 0 : (t.y >= n ? n - 1 : t.y);
  return maps.depths[(static_cast<std::size_t>(layer) * n + y) * n + x];
}
inline vec4 shadowFilterTexel(const ShadowMapView& maps, int layer, ivec2 t) {
  if (!maps.filters) return vec4(1.0f);
  const int n = maps.size;
  const int x = t.x < 0 ? 0 : (t.x >= n ? n - 1 : t.x);
  const int y = t.y < 0 ? 0 : (t.y >= n ? n - 1 : t.y);
  return maps.filters[(static_cast<std::size_t>(layer) * n + y) * n + x];
}
inline float shadowMapSize(const ShadowMapView& maps) {
  return float(maps.size);
}
#define IBL_SHADOW_MAPS const ShadowMapView &maps,
#define IBL_SHADOW_ARG maps,
#define IBL_SHADOW_ONLY maps
#else
#define IBL_SHADOW_MAPS
#define IBL_SHADOW_ARG
#define IBL_SHADOW_ONLY
// Defined by the shader over its buffers (shaders/view/shading.glsl).
ShadowLayer shadowLayerAt(int i);
float shadowDepthTexel(int layer, ivec2 t);
vec4 shadowFilterTexel(int layer, ivec2 t);  // rgb: what passes; a: the stored depth
float shadowMapSize();
#endif

// Whether the receiver at depth receiverDepth (world) is lit at texel coordinates t, by bilinear
// percentage-closer filtering of the 2 x 2 texels around t: each compared with the receiver
// plane's depth at its center, less `bias`; a texel whose filter lies in front of the receiver
// passes its color, less the receiver's own crossing `own` (a surface that transmits is among
// the surfaces the filter multiplies, as it lies in front of the opaque depth: 1 for the others).
// Returns the light that passes (rgb), or with `blockers` the sum and count of the depths
// (world) of the nearest surfaces, opaque or transmissive, that block or tint it, in (x, y).
IBL_FN vec3 shadowCompareBilinear(IBL_SHADOW_MAPS int layer, ShadowLayer l, vec3 p, vec3 n, vec2 t,
                                  float depth, float bias, float limit, bool blockers, vec3 own) {
  float mapSize = shadowMapSize(IBL_SHADOW_ONLY);
  vec2 base = floor(t - vec2(0.5f));
  vec2 f = t - vec2(0.5f) - base;
  vec3 result = vec3(0.0f);
  for (int k = 0; k < 4; ++k) {
    vec2 offset = vec2(float(k & 1), float(k >> 1));
    vec2 center = base + offset + vec2(0.5f);
    float stored = shadowDepthTexel(IBL_SHADOW_ARG layer, ivec2(base + offset));
    vec4 passed = shadowFilterTexel(IBL_SHADOW_ARG layer, ivec2(base + offset));
    float occluder = shadowWorldDepth(l, stored);
    float tint = shadowWorldDepth(l, passed.w);
    float receiver = receiverPlaneDepth(l, p, n, center, mapSize, depth, limit) - bias;
    float w = (offset.x > 0.5f ? f.x : 1.0f - f.x) * (offset.y > 0.5f ? f.y : 1.0f - f.y);
    bool blocked = stored < 1.0f && occluder < receiver;
    bool tinted = passed.w < 1.0f && tint < receiver;
    if (blockers) {
      if (tinted)
        result += vec3(tint, 1.0f, 0.0f);
      else if (blocked)
        result += vec3(occluder, 1.0f, 0.0f);
    } else if (!blocked) {
      result += w * (tinted ? min(vec3(passed) / max(own, vec3(1e-4f)), vec3(1.0f)) : vec3(1.0f));
    }
  }
  return result;
}

// The share of `c`'s light that reaches point p (normal n, turned here toward the light's side) in
// layer `layer`, per channel (colored by the surfaces that transmit, the receiver's own crossing
// `own` left out: shadowCompareBilinear): the blocker search, then
// percentage-closer filtering over the penumbra the light's size gives at the blockers' mean
// depth (at least kShadowMinFilterTexels, at most shadowMaxFilterTexels). Outside the layer: 1.
IBL_FN vec3 shadowLayerVisibility(IBL_SHADOW_MAPS ShadowCaster c, int layer, vec3 p, vec3 n,
                                  vec3 own) {
  float mapSize = shadowMapSize(IBL_SHADOW_ONLY);
  ShadowLayer l = shadowLayerAt(IBL_SHADOW_ARG layer);
  ShadowProjection at = shadowProject(l, p, mapSize);
  // Normal offset: the point is moved off its surface by a texel's size (the more, the more
  // the surface turns from the light), then projected again.
  vec3 toLight = l.perspective != 0 ? normalize(l.origin - p) : -l.forward;
  // On the light's side of the surface (a light behind a surface that transmits).
  if (dot(n, toLight) < 0.0f) n = -n;
  float cosAngle = abs(dot(n, toLight));
  float sinAngle = sqrt(max(1.0f - cosAngle * cosAngle, 0.0f));
  vec3 q = p + n * (kShadowNormalOffsetTexels * at.texelSize * sinAngle);
  at = shadowProject(l, q, mapSize);
  if (at.depth <= l.near || at.texel.x < 0.0f || at.texel.y < 0.0f || at.texel.x > mapSize ||
      at.texel.y > mapSize)
    return vec3(1.0f);
  float slope = min(sinAngle / max(cosAngle, 1e-4f), kShadowMaxSlope);
  float bias = (kShadowDepthBiasTexels + kShadowSlopeBiasTexels * slope) * at.texelSize;
  float maxFilter = shadowMaxFilterTexels(mapSize);
  float limit = at.texelSize * (maxFilter + 2.0f) * 4.0f;
  float filterTexels = kShadowMinFilterTexels;
  if (c.size > 0.0f) {
    // The region where blockers of any part of the light project: for a light of radius r at
    // the eye, r (z_r - z) / z at depth z, largest at the near plane; for the sun, the depth
    // difference times tan of its angular radius.
    float search = l.perspective != 0 ? c.size * (at.depth - l.near) / at.depth /
                                            (2.0f * l.near * l.scale / mapSize)
                                      : (at.depth - l.near) * c.size / at.texelSize;
    search = clamp(search, 1.0f, maxFilter);
    vec2 found = vec2(0.0f);
    for (int i = 0; i < kShadowTaps; ++i)
      found += vec2(shadowCompareBilinear(IBL_SHADOW_ARG layer, l, q, n,
                                          at.texel + search * shadowDiskTap(i), at.depth, bias,
                                          limit, true, own));
    if (found.y == 0.0f) return vec3(1.0f);
    float blocker = found.x / found.y;
    // The penumbra's half width at the receiver (similar triangles, PCSS eq. 1): r (z_r - z_b)
    // / z_b from a light of radius r; (z_r - z_b) tan(angular radius) from the sun.
    float penumbra = l.perspective != 0 ? c.size * (at.depth - blocker) / max(blocker, 1e-6f)
                                        : (at.depth - blocker) * c.size;
    filterTexels = clamp(penumbra / at.texelSize, kShadowMinFilterTexels, maxFilter);
  }
  vec3 lit = vec3(0.0f);
  for (int i = 0; i < kShadowTaps; ++i)
    lit += shadowCompareBilinear(IBL_SHADOW_ARG layer, l, q, n,
                                 at.texel + filterTexels * shadowDiskTap(i), at.depth, bias, limit,
                                 false, own);
  return lit / float(kShadowTaps);
}

// The share of `c`'s light that reaches p (normal n, turned here toward the light's side), per
// channel: the layer that holds p (the cascade of its view depth, the cube face of its direction
// from the light, the single layer), filtered. 1 without a shadow. `own`: what the receiver's
// surface itself lets through toward the light (shadowReceiverCrossing in split_sum.h; 1 for a
// surface that transmits nothing), which the maps' filters hold too.
IBL_FN vec3 shadowVisibility(IBL_SHADOW_MAPS ShadowCaster c, vec3 p, vec3 n, vec3 own) {
  if (c.kind == kShadowNone || c.layerCount == 0) return vec3(1.0f);
  if (c.kind == kShadowCascades) {
    int i = shadowCascadeIndex(dot(p - c.viewOrigin, c.viewForward), c.splits, c.layerCount);
    if (i < 0) return vec3(1.0f);
    return shadowLayerVisibility(IBL_SHADOW_ARG c, c.firstLayer + i, p, n, own);
  }
  if (c.kind == kShadowCube)
    return shadowLayerVisibility(
        IBL_SHADOW_ARG c, c.firstLayer + directionToFace(p - c.lightPosition).face, p, n, own);
  return shadowLayerVisibility(IBL_SHADOW_ARG c, c.firstLayer, p, n, own);
}

IBL_END

#endif
