// API: internal (may change without notice; math shared with the shaders)
// Irradiance volumes with visibility (Majercik, Guertin, Nowrouzezahrai & McGuire 2019,
// "Dynamic Diffuse Global Illumination with Ray-Traced Irradiance Fields", JCGT 8(2)): a grid
// of probes, each with its irradiance over the sphere of directions and the mean and mean
// squared distance to the first surface, in octahedral maps; a point reads the eight probes
// around it, weighed by trilinear position, by the side of the surface they lie on, and by
// Chebyshev's bound on the probe seeing the point. C++ and GLSL (see lang.h): the CPU split
// sum (src/render/irradiance_volume.cpp) and the viewer's shader run the same loop, each with
// its own two texture reads:
//
//   for (int corner = 0; corner < 8; ++corner) {
//     int probe = volumeCornerProbe(g, p, corner);
//     VolumeCorner c = volumeCorner(g, p, n, v, corner, <the probe's relocation record>);
//     if (c.weight <= 0.0f) continue;
//     vec2 moments = <the distance atlas at volumeAtlasTexel(g, probe, c.direction, distance)>;
//     float w = volumeCornerWeight(g, c, moments);
//     sum += w * <the irradiance atlas at volumeAtlasTexel(g, probe, diffuseDirection, ...)>;
//     total += w;
//   }
//   irradiance = volumeIrradiance(sum, total);
#ifndef IBL_SHARED_IRRADIANCE_VOLUME_H
#define IBL_SHARED_IRRADIANCE_VOLUME_H
#include "ibl/shared/color.h"
#include "ibl/shared/lang.h"
#include "ibl/shared/sampling.h"

IBL_BEGIN

// The weighting rules, as bits of VolumeGrid.rules (all on by default; the tests and the
// measurements switch them off one by one).
const int kVolumeBackface = 1;    // the smooth backface weight
const int kVolumeVisibility = 2;  // Chebyshev's visibility from the distance moments
const int kVolumeAllRules = 3;

// The grid: probe (i, j, k) sits at origin + spacing * (i, j, k) plus its relocation offset;
// its linear index is i + nx (j + ny k). Each probe owns a tile of (texels + 2)^2 in each atlas
// (the octahedral map with a one-texel border), tile (i + nx j, k) of the atlas.
struct VolumeGrid {
  vec3 origin;           // world position of probe (0, 0, 0) before relocation
  vec3 spacing;          // between neighbouring probes, per axis (> 0)
  ivec3 counts;          // probes per axis (>= 1)
  float normalBias;      // the shaded point moves by normalBias * n + viewBias * v, in units of
  float viewBias;        // the smallest spacing (Majercik et al. 2019, section 4.3)
  int irradianceTexels;  // interior size of an irradiance tile
  int distanceTexels;    // interior size of a distance tile
  int rules;             // kVolume* bits
};

// The sign of x with sign(0) = 1 (the octahedral fold needs no zero).
IBL_FN vec2 signNotZero(vec2 x) {
  vec2 s;
  s.x = x.x >= 0.0f ? 1.0f : -1.0f;
  s.y = x.y >= 0.0f ? 1.0f : -1.0f;
  return s;
}

// The octahedral map of unit directions onto [-1, 1]^2 (Cigolle et al. 2014, "A Survey of
// Efficient Representations for Independent Unit Vectors", JCGT 3(2), listing 1): the +Z half
// inside the diamond |u| + |v| <= 1, the -Z half folded over its corners.
IBL_FN vec2 octahedralEncode(vec3 d) {
  vec2 p = vec2(d.x, d.y) * (1.0f / (abs(d.x) + abs(d.y) + abs(d.z)));
  if (d.z < 0.0f) p = (vec2(1.0f) - abs(vec2(p.y, p.x))) * signNotZero(p);
  return p;
}

// Its inverse: the unit direction of a point of [-1, 1]^2.
IBL_FN vec3 octahedralDecode(vec2 e) {
  vec3 d = vec3(e.x, e.y, 1.0f - abs(e.x) - abs(e.y));
  if (d.z < 0.0f) {
    vec2 folded = (vec2(1.0f) - abs(vec2(d.y, d.x))) * signNotZero(vec2(d.x, d.y));
    d.x = folded.x;
    d.y = folded.y;
  }
  return normalize(d);
}

// Probe (i, j, k)'s linear index.
IBL_FN int volumeProbeIndex(VolumeGrid g, ivec3 c) {
  return c.x + g.counts.x * (c.y + g.counts.y * c.z);
}

// Probe `index`'s place on the grid, before its relocation offset.
IBL_FN vec3 volumeGridPosition(VolumeGrid g, int index) {
  int nx = g.counts.x, ny = g.counts.y;
  ivec3 c = ivec3(index % nx, index / nx % ny, index / (nx * ny));
  return g.origin + g.spacing * vec3(float(c.x), float(c.y), float(c.z));
}

// The power of the cosine lobe over which a texel of the distance map averages the distances
// (section 4.1): sharper than the irradiance's cosine, so that walls keep their edges.
const float kVolumeDistanceSharpness = 50.0f;

// Where the texel of direction d of a probe's tile lies in an atlas, in texels from the atlas'
// top-left corner (continuous: texel (x, y) covers [x, x + 1) x [y, y + 1)); `texels` is the
// tile's interior size. Bilinear filtering at this point stays inside the tile: its border
// repeats the interior across the map's folds (volumeBorderSource).
IBL_FN vec2 volumeAtlasTexel(VolumeGrid g, int probe, vec3 d, int texels) {
  int column = probe % (g.counts.x * g.counts.y);
  int row = probe / (g.counts.x * g.counts.y);
  vec2 tile = vec2(float(column), float(row)) * float(texels + 2);
  return tile + vec2(1.0f) + (octahedralEncode(d) * 0.5f + vec2(0.5f)) * float(texels);
}

// The interior texel a border texel of a tile copies ((x, y) in [0, texels + 1]^2, the interior
// [1, texels]): across an edge of the octahedral map, the texel mirrored along that edge; at a
// corner, the opposite corner (Majercik et al. 2019, figure 5). Interior texels map to
// themselves.
IBL_FN ivec2 volumeBorderSource(ivec2 t, int texels) {
  int last = texels;  // the last interior texel
  ivec2 s = t;
  bool left = t.x == 0, right = t.x == last + 1, top = t.y == 0, bottom = t.y == last + 1;
  if ((left || right) && (top || bottom)) {
    s.x = left ? last : 1;
    s.y = top ? last : 1;
  } else if (top || bottom) {
    s.x = last + 1 - t.x;
    s.y = top ? 1 : last;
  } else if (left || right) {
    s.x = left ? 1 : last;
    s.y = last + 1 - t.y;
  }
  return s;
}

// The probe at one of the eight corners (bits: +x, +y, +z) of the grid cell holding p; points
// outside the grid read the nearest probes (the indices clamp).
IBL_FN ivec3 volumeBaseProbe(VolumeGrid g, vec3 p) {
  vec3 local = (p - g.origin) / g.spacing;
  ivec3 base;
  base.x = clamp(int(floor(local.x)), 0, g.counts.x - 1);
  base.y = clamp(int(floor(local.y)), 0, g.counts.y - 1);
  base.z = clamp(int(floor(local.z)), 0, g.counts.z - 1);
  return base;
}

IBL_FN ivec3 volumeCornerOffset(int corner) {
  ivec3 o;
  o.x = corner & 1;
  o.y = (corner >> 1) & 1;
  o.z = (corner >> 2) & 1;
  return o;
}

IBL_FN int volumeCornerProbe(VolumeGrid g, vec3 p, int corner) {
  ivec3 c = volumeBaseProbe(g, p) + volumeCornerOffset(corner);
  c.x = min(c.x, g.counts.x - 1);
  c.y = min(c.y, g.counts.y - 1);
  c.z = min(c.z, g.counts.z - 1);
  return volumeProbeIndex(g, c);
}

// One corner's part of a lookup, before its distance moments are read.
struct VolumeCorner {
  vec3 direction;  // from the probe toward the biased point (unit): where its distances are read
  float distance;  // from the probe to the biased point
  float weight;    // trilinear x backface; 0 for a probe switched off
  float trilinear;
};

// The shaded point moved off its surface (Majercik et al. 2019, section 4.3: the "self-shadow
// bias", mostly toward the viewer and a little along the normal), so that the distance moments'
// limited precision does not shadow a surface by itself. n: unit normal, v: unit toward viewer.
IBL_FN vec3 volumeBiasedPoint(VolumeGrid g, vec3 p, vec3 n, vec3 v) {
  float unit = min(min(g.spacing.x, g.spacing.y), g.spacing.z);
  return p + (g.normalBias * n + g.viewBias * v) * unit;
}

// relocation: the probe's record, xyz its offset from the grid position, w 1 when it is on and
// 0 when it was switched off (inside geometry).
IBL_FN VolumeCorner volumeCorner(VolumeGrid g, vec3 p, vec3 n, vec3 v, int corner,
                                 vec4 relocation) {
  ivec3 base = volumeBaseProbe(g, p);
  ivec3 offset = volumeCornerOffset(corner);
  ivec3 c = base + offset;
  c.x = min(c.x, g.counts.x - 1);
  c.y = min(c.y, g.counts.y - 1);
  c.z = min(c.z, g.counts.z - 1);
  vec3 probe = g.origin + g.spacing * vec3(float(c.x), float(c.y), float(c.z)) +
               vec3(relocation.x, relocation.y, relocation.z);
  // The trilinear weights from the grid positions (not the relocated ones), clamped so that a
  // point outside the grid takes its nearest layer.
  vec3 basePosition = g.origin + g.spacing * vec3(float(base.x), float(base.y), float(base.z));
  vec3 alpha = clamp((p - basePosition) / g.spacing, vec3(0.0f), vec3(1.0f));
  vec3 tri =
      mix(vec3(1.0f) - alpha, alpha, vec3(float(offset.x), float(offset.y), float(offset.z)));
  VolumeCorner r;
  r.trilinear = tri.x * tri.y * tri.z;
  vec3 towardPoint = volumeBiasedPoint(g, p, n, v) - probe;
  r.distance = length(towardPoint);
  r.direction = r.distance > 0.0f ? towardPoint / r.distance : n;
  r.weight = relocation.w > 0.0f ? 1.0f : 0.0f;
  if ((g.rules & kVolumeBackface) != 0) {
    // Section 4.2: a smooth backface test, from the unbiased point, that never reaches 0 (0.2).
    vec3 toProbe = probe - p;
    float len = length(toProbe);
    float facing = len > 0.0f ? dot(toProbe / len, n) : 1.0f;
    float towardSide = max(0.0001f, (facing + 1.0f) * 0.5f);
    r.weight *= towardSide * towardSide + 0.2f;
  }
  return r;
}

// Chebyshev's upper bound on the share of the probe's rays toward the point that reach it, from
// the mean and mean squared distance of its first hits in that direction (section 4.2,
// variance shadow maps: Donnelly & Lauritzen 2006); 1 when the point is nearer than the mean.
IBL_FN float chebyshevVisibility(float distance, vec2 moments) {
  float mean = moments.x;
  if (distance <= mean) return 1.0f;
  float variance = abs(mean * mean - moments.y);
  float d = distance - mean;
  float bound = variance / (variance + d * d);
  return max(bound * bound * bound, 0.0f);  // cubed: sharper shadows (the paper's listing)
}

// The corner's final weight: backface x visibility, small weights crushed (below 0.2, a cubic
// ramp to zero: light leaks from barely visible probes fade out), then trilinear (the paper's
// listing 2, in that order).
IBL_FN float volumeCornerWeight(VolumeGrid g, VolumeCorner c, vec2 moments) {
  if (c.weight <= 0.0f) return 0.0f;
  float w = c.weight;
  if ((g.rules & kVolumeVisibility) != 0) w *= chebyshevVisibility(c.distance, moments);
  w = max(w, 0.000001f);
  const float crush = 0.2f;
  if (w < crush) w *= w * w / (crush * crush);
  return w * c.trilinear;
}

IBL_FN vec3 volumeIrradiance(vec3 sum, float total) {
  return total > 0.0f ? sum / total : vec3(0.0f);
}

// How much of the diffuse light the volume gives at p: 1 within half a spacing of its outer
// probes (the box the grid's cells fill), fading smoothly to 0 half a spacing further out,
// where the local probes and the distant environment take over.
IBL_FN float volumeCoverage(VolumeGrid g, vec3 p) {
  vec3 last = g.origin +
              g.spacing * vec3(float(g.counts.x - 1), float(g.counts.y - 1), float(g.counts.z - 1));
  vec3 outside =
      max(max(g.origin - p, p - last) - 0.5f * g.spacing, vec3(0.0f)) / (0.5f * g.spacing);
  vec3 t = clamp(vec3(1.0f) - outside, vec3(0.0f), vec3(1.0f));
  vec3 s = t * t * (vec3(3.0f) - 2.0f * t);
  return s.x * s.y * s.z;
}

// Direction i of n spread evenly over the sphere (sphericalFibonacciPoint), turned by
// `rotation`: the rays one frame of the live update traces from each probe (Majercik et al.
// 2019, section 5: a new random rotation every frame, so that the frames' rays fill the sphere).
IBL_FN vec3 volumeRayDirection(int i, int n, mat3 rotation) {
  return rotation * sphericalFibonacciPoint(i, n);
}

// A texel after one frame of the update (section 5): the frame's estimate, the weighted mean of
// its rays (sum of w x value over sum of w: the normalization makes it an estimate of the
// texel, whatever the number of rays), blended with what the texel held; `hysteresis` is the
// share kept (0.9 to 0.97 in the paper). No ray weighed anything: the texel stays.
IBL_FN vec3 volumeBlend(vec3 previous, vec3 weightedSum, float weightSum, float hysteresis) {
  if (weightSum <= 0.0f) return previous;
  return mix(weightedSum / weightSum, previous, hysteresis);
}

// The largest factor by which the volume brightens a probe's specular (volumeSpecularScale).
const float kVolumeMaxSpecularScale = 4.0f;

// The normalization of a probe's specular by the irradiance at the shaded point (Lazarov 2013,
// "Getting More Physical in Call of Duty: Black Ops II", SIGGRAPH course: environment maps
// scaled by the ratio of the lightmap's irradiance to the probe's own): the luminance of the
// volume's irradiance over that of the irradiance the probes and the distant environment give
// at the same point and direction, so that a probe captured in the light does not shine into a
// dark corner. Blended toward 1 where the volume does not cover (coverage), at most
// kVolumeMaxSpecularScale.
IBL_FN float volumeSpecularScale(vec3 volume, vec3 source, float coverage) {
  float ratio = min(luminance(volume) / max(luminance(source), 1e-6f), kVolumeMaxSpecularScale);
  return mix(1.0f, ratio, coverage);
}

IBL_END

#endif
