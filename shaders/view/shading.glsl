// The split-sum shading of a surface point: the formulas of ibl/shared/split_sum.h (which
// shadeSplitSum in src/render/renderer.cpp calls too) with the GPU's lookups: samplerCube
// trilinear filtering, the DFG table bilinear and clamped. Needs view/frame.glsl.
#include "ibl/shared/lights.h"
#include "ibl/shared/sh.h"
#include "ibl/shared/probes.h"
#include "ibl/shared/split_sum.h"

// The frame's shading switches (splitSumSwitches in src/render/renderer.cpp fills them).
SplitSumSwitches frameSwitches() {
  SplitSumSwitches s;
  s.terms = frame.terms.x;
  s.multipleScattering = frame.terms.y != 0;
  s.dominantDirections = frame.terms.z != 0;
  s.specularOcclusion = frame.terms.w != 0;
  s.disneyDiffuse = frame.models.x == 0;
  s.ltcAreaLights = frame.viewport.z != 0.0;
  return s;
}

// irradianceSh9 / pi (src/math/sh.cpp); the host folded A_l / pi into the coefficients.
vec3 irradianceSh9OverPi(vec3 n) {
  vec3 sum = vec3(0.0);
  for (int k = 0; k < 9; ++k) sum += frame.sh[k].rgb * shBasis(k, n);
  return sum;
}

ShadingLight lightAt(int i) {
  ShadingLight l;
  vec4 a = lightData[5 * i], b = lightData[5 * i + 1], c = lightData[5 * i + 2],
       d = lightData[5 * i + 3], e = lightData[5 * i + 4];
  l.type = int(a.w);
  l.position = a.xyz;
  l.direction = b.xyz;
  l.radius = b.w;
  l.up = c.xyz;
  l.width = c.w;
  l.color = d.xyz;
  l.height = d.w;
  l.cosInner = e.x;
  l.cosOuter = e.y;
  l.invSquaredRange = e.z;
  return l;
}

// An IES profile's candela toward unit w leaving the light, over its peak (which the light's
// color carries): the table's bilinear interpolation with exact weights; 1 without a profile.
float iesProfileFactor(ShadingLight l, float profile, vec3 w) {
  if (profile < 0.0) return 1.0;
  vec2 angles = iesAngles(iesNadir(l), w);
  vec2 p = vec2(angles.y / 360.0 * float(kIesTableColumns - 1),
                angles.x / 180.0 * float(kIesTableRows - 1));
  ivec2 i = min(ivec2(p), ivec2(kIesTableColumns - 2, kIesTableRows - 2));
  vec2 f = p - vec2(i);
  i.y += int(profile) * kIesTableRows;
  return mix(mix(texelFetch(iesTable, i, 0).r, texelFetch(iesTable, i + ivec2(1, 0), 0).r, f.x),
             mix(texelFetch(iesTable, i + ivec2(0, 1), 0).r, texelFetch(iesTable, i + ivec2(1, 1), 0).r, f.x),
             f.y);
}

// The nearest emitter (area light or sun) the ray meets closer than maxDistance, as the CPU's
// nearestLight (src/render/renderer.cpp) finds it: its luminance; `surface` false for the sun.
bool nearestEmitter(Ray r, float maxDistance, out vec3 radiance, out bool surface) {
  float best = maxDistance;
  bool found = false;
  radiance = vec3(0.0);
  for (int i = 0; i < frame.models.w; ++i) {
    ShadingLight l = lightAt(i);
    float t = emitterDistance(l, r.origin, r.direction);
    if (t >= 0.0 && t < best) {
      best = t;
      radiance = emitterRadiance(l, r.direction);
      found = true;
    }
  }
  surface = best < kSunDistance;
  return found;
}

// The LTC table's entry, interpolated as ltcTableLookup (src/render/ltc.cpp) does.
vec4 ltcTableEntry(float roughness, float NoV) {
  int size = textureSize(ltcTable, 0).x;
  vec2 p = ltcTablePosition(roughness, NoV, float(size));
  ivec2 i = min(ivec2(p), ivec2(size - 2));
  vec2 f = p - vec2(i);
  return mix(mix(texelFetch(ltcTable, i, 0), texelFetch(ltcTable, i + ivec2(1, 0), 0), f.x),
             mix(texelFetch(ltcTable, i + ivec2(0, 1), 0), texelFetch(ltcTable, i + ivec2(1, 1), 0), f.x),
             f.y);
}

// The environment's split sum plus the scene's lights (shadeSplitSum and shadeLightsRealTime in
// src/render/renderer.cpp) at a point at `position`.
vec3 shadeSplitSum(vec3 position, vec3 n, vec3 view, SplitSumMaterial m) {
  SplitSumSwitches s = frameSwitches();
  SplitSumLookup look = splitSumLookup(n, view, m.roughness, s);
  vec3 dfg = textureLod(dfgLut, vec2(look.NoV, m.roughness), 0.0).rgb;
  vec3 prefiltered = vec3(0.0), irradiance = vec3(0.0);
  vec3 lit = vec3(0.0);
  if (frame.models.w > 0) {
    SplitSumMaterial direct = m;
    direct.occlusion = 1.0;
    direct.emissive = vec3(0.0);
    vec4 ltc = vec4(1.0, 0.0, 0.0, 1.0);
    if (s.ltcAreaLights) ltc = ltcTableEntry(m.roughness, look.NoV);
    for (int i = 0; i < frame.models.w; ++i) {
      ShadingLight l = lightAt(i);
      LightIncidence inc = lightIncidence(l, position, n, view, m.roughness, s, ltc);
      float profile = iesProfileFactor(l, lightData[5 * i + 4].w, normalize(position - l.position));
      lit += l.color * profile * lightRadiance(direct, n, view, inc, dfg.xy, s);
    }
  }
  if (frame.lods.w < 0.5) return lit + splitSumRadiance(m, look.NoV, dfg, prefiltered, irradiance, s);
  if (s.terms != 1) {
    float lod = specularLodForRoughness(m.roughness, frame.lods.x, frame.lods.y > 0.5);
    prefiltered = textureLod(specularMap, look.specularDirection, lod).rgb;
  }
  if (s.terms != 2)
    irradiance = frame.models.y == 0 ? textureLod(irradianceMap, look.diffuseDirection, 0.0).rgb
                                     : irradianceSh9OverPi(look.diffuseDirection);
  return lit + splitSumRadiance(m, look.NoV, dfg, prefiltered, irradiance, s);
}
