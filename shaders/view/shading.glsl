// The split-sum shading of a surface point: the formulas of ibl/shared/split_sum.h (which
// shadeSplitSum in src/render/renderer.cpp calls too) with the GPU's lookups: samplerCube
// trilinear filtering, the DFG table bilinear and clamped. Needs view/frame.glsl.
#include "ibl/shared/clusters.h"
#include "ibl/shared/lights.h"
#include "ibl/shared/sh.h"
#include "ibl/shared/probes.h"
#include "view/shadow_maps.glsl"
#include "view/volume.glsl"
#include "ibl/shared/split_sum.h"
#include "ibl/shared/screen_space_reflections.h"

// The sheen's exact Lambda reads its table from the frame's buffer (brdf.h declares this).
float charlieTableEntry(int k) {
  return charlieTable[k];
}

// Specialization constants (SceneRenderer::Impl::scenePipeline): whether the lights cast shadows
// and whether area lights go through LTCs. The pipeline of each variant has only its own code.
layout(constant_id = 0) const bool kCastShadows = false;
layout(constant_id = 1) const bool kLtcAreaLights = true;

// The frame's shading switches (splitSumSwitches in src/render/renderer.cpp fills them).
SplitSumSwitches frameSwitches() {
  SplitSumSwitches s;
  s.terms = frame.terms.x;
  s.multipleScattering = frame.terms.y != 0;
  s.dominantDirections = frame.terms.z != 0;
  s.specularOcclusion = frame.terms.w != 0;
  s.disneyDiffuse = frame.models.x == 0;
  s.ltcAreaLights = kLtcAreaLights;
  s.sheenVisibility = frame.shading.x;
  s.specularMicroOcclusion = frame.shading.y != 0;
  s.multiBounceOcclusion = frame.shading.z != 0;
  return s;
}

// irradianceSh9 / pi (src/math/sh.cpp); the host folded A_l / pi into the coefficients.
vec3 irradianceSh9OverPi(vec3 n) {
  vec3 sum = vec3(0.0);
  for (int k = 0; k < 9; ++k) sum += frame.sh[k].rgb * shBasis(k, n);
  return sum;
}

// The distant environment's irradiance over pi toward d: the irradiance cube or the SH9.
vec3 distantIrradiance(vec3 d) {
  return frame.models.y == 0 ? textureLod(irradianceMap, d, 0.0).rgb : irradianceSh9OverPi(d);
}

// The clustered light lists (buildLightClusters in src/render/light_clusters.cpp): the grid of
// this frame, and (first, count) in clusterData of the lights that may reach the cluster of a
// point seen at framebuffer point `pixel`, or of the emitters the tile's rays may meet.
LightClusterGrid frameClusterGrid() {
  LightClusterGrid g;
  g.tileSize = frame.clusterGrid.x;
  g.tilesX = frame.clusterGrid.y;
  g.tilesY = frame.clusterGrid.z;
  g.slices = frame.clusterGrid.w;
  g.near = frame.clusterDepths.x;
  g.far = frame.clusterDepths.y;
  g.perspective = int(frame.clusterDepths.z);
  return g;
}
uvec2 clusterLights(vec2 pixel, vec3 position) {
  float z = dot(position - frame.cameraPosition.xyz, frame.cameraForward.xyz);
  int c = clusterIndex(frameClusterGrid(), pixel, z);
  return uvec2(clusterData[2 * c], clusterData[2 * c + 1]);
}
uvec2 tileEmitters(vec2 pixel) {
  LightClusterGrid g = frameClusterGrid();
  int c = clusterCount(g) + clusterTile(g, pixel);
  return uvec2(clusterData[2 * c], clusterData[2 * c + 1]);
}

// Light i's record (ibl/shared/light_record.h; frame.glsl's Lights).
LightRecord lightRecordAt(int i) {
  int b = kLightRecordVec4s * i;
  return LightRecord(lightData[b], lightData[b + 1], lightData[b + 2], lightData[b + 3],
                     lightData[b + 4]);
}
ShadingLight lightAt(int i) {
  return unpackLight(lightRecordAt(i));
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
// Only the emitters of the tile of framebuffer point `pixel` (the ray's) are tried.
bool nearestEmitter(Ray r, vec2 pixel, float maxDistance, out vec3 radiance, out bool surface) {
  float best = maxDistance;
  bool found = false;
  radiance = vec3(0.0);
  uvec2 list = frame.models.w > 0 ? tileEmitters(pixel) : uvec2(0u);
  for (uint k = list.x; k < list.x + list.y; ++k) {
    ShadingLight l = lightAt(int(clusterData[k]));
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

ProbeVolume probeVolumeAt(int base) {
  ProbeVolume v;
  v.center = probeData[base].xyz;
  v.shape = int(probeData[base].w);
  v.halfExtent = probeData[base + 1].xyz;
  v.worldToLocal = mat3(probeData[base + 2].xyz, probeData[base + 3].xyz, probeData[base + 4].xyz);
  return v;
}

// The local probes' share of the lighting (lookupProbes in src/render/probe.cpp, with the GPU's
// lookups): prefiltered and irradiance weighed by each probe's share, premultiplied by the
// capture's coverage (the maps' alpha); returns the coverage reached by the specular (x) and
// the irradiance (y).
vec2 localProbes(vec3 position, vec3 r, vec3 d, float roughness, int terms,
                 out vec3 prefiltered, out vec3 irradiance) {
  prefiltered = vec3(0.0);
  irradiance = vec3(0.0);
  vec2 coverage = vec2(0.0);
  bool wantSpecular = terms != 1, wantDiffuse = terms != 2;
  int flags = int(frame.probes.z);
  for (int i = 0; i < int(frame.probes.x); ++i) {
    if ((!wantSpecular || coverage.x >= 1.0) && (!wantDiffuse || coverage.y >= 1.0)) break;
    int base = 11 * i;
    ProbeVolume influence = probeVolumeAt(base + 6);
    float weight = influenceWeight(influence, probeData[base + 7].w, position);
    float share = probeShare(weight, coverage.x);
    float diffuseShare = probeShare(weight, coverage.y);
    if (share <= 0.0 && diffuseShare <= 0.0) continue;
    ParallaxLookup look;
    look.direction = r;
    look.roughness = roughness;
    if (probeData[base].w > 0.5 && (flags & 1) != 0)
      look = parallaxCorrectedLookup(probeVolumeAt(base + 1), probeData[base].xyz, position, r,
                                     roughness, (flags & 2) != 0);
    if (wantSpecular && share > 0.0) {
      float lod = specularLodForRoughness(look.roughness, frame.probes.y, (flags & 4) != 0);
      vec4 s = textureLod(probeSpecularMaps, vec4(look.direction, float(i)), lod);
      prefiltered += share * s.rgb;
      coverage.x = coverageAfterProbe(coverage.x, share, s.a);
    }
    if (wantDiffuse && diffuseShare > 0.0) {
      vec4 e = textureLod(probeIrradianceMaps, vec4(d, float(i)), 0.0);
      irradiance += diffuseShare * e.rgb;
      coverage.y = coverageAfterProbe(coverage.y, diffuseShare, e.a);
    }
  }
  return coverage;
}

// The prefiltered light along `direction` at `roughness`: the local probes first, the distant
// environment for the rest (shadeSplitSum's prefilteredLight, as the coat and the transmission
// read it).
vec3 prefilteredAlong(vec3 position, vec3 direction, float roughness, int terms) {
  vec3 light = vec3(0.0), unused;
  float rest = 1.0;
  if (frame.probes.x > 0.0)
    rest -= localProbes(position, direction, direction, roughness, 2, light, unused).x;
  if (frame.lods.w >= 0.5 && rest > 0.0 && terms != 1) {
    float lod = specularLodForRoughness(roughness, frame.lods.x, frame.lods.y > 0.5);
    light += rest * textureLod(specularMap, direction, lod).rgb;
  }
  return light;
}

// The environment's split sum plus the scene's lights (shadeSplitSum and shadeLightsRealTime in
// src/render/renderer.cpp) at a point at `position`, under a sheen layer (sheen: color and
// roughness of KHR_materials_sheen; color 0: none) that scales the rest by its albedo scaling.
// The lights evaluated are those of the point's cluster (seen at framebuffer point `pixel`).
// bentNormal: the irradiance's direction from the screen-space occlusion (0: the normal).
// reflection: the screen-space reflection (view/ssr.frag; 0: none), composed before the probes.
// The opaque frame behind a transmissive surface at position (n its unit normal, view toward the
// eye), where the refracted ray leaves its volume: TransmissionFrame::at on the CPU
// (src/render/transmission_frame.cpp), the same projection (ibl/shared/ambient_occlusion.h).
vec4 transmissionFrameTexel(vec3 position, vec3 n, vec3 view, SplitSumMaterial m) {
  vec3 exit = position + volumeExitOffset(n, view, m.thickness, m.ior);
  vec3 w = exit - frame.cameraPosition.xyz;
  vec3 viewSpace = vec3(dot(w, normalize(frame.cameraRight.xyz)),
                        dot(w, normalize(frame.cameraUp.xyz)), dot(w, frame.cameraForward.xyz));
  if (!frameHoldsDepth(viewSpace.z, frame.projection.z)) return vec4(0.0);
  ScreenProjection s;
  s.size = frame.viewport.xy;
  s.scale = frame.projection.xy;
  s.perspective = frame.projection.z;
  vec2 uv = projectToPixel(s, viewSpace) / s.size;
  return textureLod(transmissionFrame, uv,
                    transmissionFrameLod(frame.viewport.x, m.roughness, m.ior));
}

vec3 shadeSplitSum(vec3 position, vec2 pixel, vec3 n, vec3 view, SplitSumMaterial m, vec4 sheen,
                   vec3 bentNormal, vec4 reflection) {
  SplitSumSwitches s = frameSwitches();
  bool sheenOnly = s.terms == 3;
  if (sheenOnly) s.terms = 0;
  bool hasSheen = max(sheen.r, max(sheen.g, sheen.b)) > 0.0;
  bool shadeSheen = hasSheen && (frame.terms.x == 0 || sheenOnly);
  vec3 emissive = m.emissive;
  m.emissive = vec3(0.0);
  SplitSumLookup look = splitSumLookup(n, view, m.roughness, s);
  look = anisotropicLookup(look, n, view, m, s);
  if (bentNormal != vec3(0.0)) look = bendDiffuseLookup(look, bentNormal, view, m.roughness, s);
  // The isotropic tables at the lobe's albedo-equivalent roughness (KHR_materials_anisotropy).
  float lobeRoughness = tableRoughness(m);
  vec3 dfg = textureLod(dfgLut, vec2(look.NoV, lobeRoughness), 0.0).rgb;
  // Disney's diffuse (the table's third channel) at the material's own roughness.
  if (lobeRoughness != m.roughness) dfg.z = textureLod(dfgLut, vec2(look.NoV, m.roughness), 0.0).b;
  // The sheen's table at the clamped roughness, and the scaling of the layer below.
  float sheenRoughness = max(sheen.w, kMinSheenRoughness);
  float sheenE = hasSheen ? textureLod(sheenDfgLut, vec2(look.NoV, sheenRoughness), 0.0).r : 0.0;
  float belowScale = sheenOnly ? 0.0 : (hasSheen ? sheenAlbedoScaling(sheen.rgb, sheenE) : 1.0);
  vec3 prefiltered = vec3(0.0), irradiance = vec3(0.0);
  vec3 lit = vec3(0.0);
  // KHR_materials_clearcoat: the coat's lobe at its own normal and roughness over the rest, which
  // it scales by belowCoat (its emission already attenuated by fragmentSurface).
  bool coat = m.clearcoat > 0.0 && !sheenOnly;
  float belowCoat =
      m.clearcoat > 0.0 ? 1.0 - clearcoatWeight(m.clearcoat, dot(m.clearcoatNormal, view)) : 1.0;
  SplitSumLookup coatLook = splitSumLookup(m.clearcoatNormal, view, m.clearcoatRoughness, s);
  vec2 coatDfg =
      coat ? textureLod(dfgLut, vec2(coatLook.NoV, m.clearcoatRoughness), 0.0).rg : vec2(0.0);
  if (frame.models.w > 0) {
    SplitSumMaterial direct = m;
    direct.occlusion = 1.0;
    vec4 ltc = vec4(1.0, 0.0, 0.0, 1.0);
    vec4 coatLtc = vec4(1.0, 0.0, 0.0, 1.0);
    if (s.ltcAreaLights) ltc = ltcTableEntry(lobeRoughness, look.NoV);
    if (s.ltcAreaLights && coat) coatLtc = ltcTableEntry(m.clearcoatRoughness, coatLook.NoV);
    float sheenAlpha = alphaFromRoughness(sheenRoughness);
    uvec2 list = clusterLights(pixel, position);
    for (uint k = list.x; k < list.x + list.y; ++k) {
      int i = int(clusterData[k]);
      LightRecord record = lightRecordAt(i);
      ShadingLight l = unpackLight(record);
      // The light's shadow first: what it hides costs nothing more. A surface that transmits
      // leaves its own crossing out of the maps' filters.
      vec3 visible =
          kCastShadows ? shadowVisibility(shadowCasterAt(i), position, n,
                                          shadowReceiverCrossing(direct, n,
                                                                 directionToLight(l, position)))
                       : vec3(1.0);
      if (visible == vec3(0.0)) continue;
      LightIncidence inc = lightIncidence(l, position, n, view, lobeRoughness, s, ltc);
      vec3 profile = visible * iesProfileFactor(l, lightRecordProfile(record),
                                                 normalize(position - l.position));
      vec3 radiance = belowScale * lightRadiance(direct, n, view, inc, dfg.xy, s);
      // KHR_materials_transmission: the light from behind the surface, through it.
      if (direct.transmission > 0.0)
        radiance += belowScale * transmittedLightRadiance(
                                     direct, n, view,
                                     lightIncidence(mirroredLight(l, position, n), position, n,
                                                    view, lobeRoughness, s, ltc),
                                     dfg.xy, s);
      if (shadeSheen)
        radiance += sheenLightRadiance(sheen.rgb, sheenAlpha, s.sheenVisibility, n, view, inc);
      radiance *= belowCoat;
      if (coat) {
        LightIncidence coatInc = lightIncidence(l, position, m.clearcoatNormal, view,
                                                m.clearcoatRoughness, s, coatLtc);
        radiance += clearcoatLightRadiance(m, view, coatInc, coatDfg, s);
      }
      lit += l.color * profile * radiance;
    }
  }
  // Local probes first, the distant environment for the rest.
  vec2 distants = vec2(1.0);
  if (frame.probes.x > 0.0)
    distants = vec2(1.0) - localProbes(position, look.specularDirection, look.diffuseDirection,
                                       m.roughness, s.terms, prefiltered, irradiance);
  float distant = distants.x;
  bool environment = frame.lods.w >= 0.5 && distant > 0.0;
  if (environment && s.terms != 1) {
    float lod = specularLodForRoughness(m.roughness, frame.lods.x, frame.lods.y > 0.5);
    prefiltered += distant * textureLod(specularMap, look.specularDirection, lod).rgb;
  }
  if (frame.lods.w >= 0.5 && distants.y > 0.0 && s.terms != 2)
    irradiance += distants.y * distantIrradiance(look.diffuseDirection);
  float specularScale = 1.0;
  if (frame.volumeTexels.z != 0) {
    // The irradiance volume gives the diffuse light where it covers, and normalizes the specular
    // of what it replaces by its irradiance (shadeSplitSum; ibl/shared/irradiance_volume.h).
    VolumeGrid g = frameVolumeGrid();
    float cover = volumeCoverage(g, position);
    if (cover > 0.0) {
      vec3 volume = volumeLookup(g, position, n, view, look.diffuseDirection);
      // Under --only specular the diffuse above was not gathered: the ratio is to the distant
      // environment's.
      vec3 source = s.terms != 2 ? irradiance
                    : (frame.lods.w >= 0.5 ? distantIrradiance(look.diffuseDirection) : vec3(0.0));
      specularScale = volumeSpecularScale(volume, source, cover);
      prefiltered *= specularScale;
      irradiance = mix(irradiance, volume, cover);
    }
  }
  SplitSumSwitches composed = s;
  if (reflection != vec4(0.0) && s.terms != 1) {
    // Lagarde & de Rousiers 2014, 4.9.5: the screen's reflection first, the probes for the rest;
    // the ambient occlusion's specular occlusion darkens the probes' share alone.
    prefiltered = composeScreenReflection(reflection, prefiltered,
                                          probeSpecularOcclusion(s, look.NoV, m));
    composed.specularOcclusion = false;
  }
  vec3 color = belowScale * splitSumRadiance(m, look.NoV, dfg, prefiltered, irradiance, composed);
  // KHR_materials_transmission: the light straight through the surface, blurred by the
  // transmission's roughness, under the sheen as the rest.
  if (m.transmission > 0.0 && s.terms != 1 && !sheenOnly) {
    vec3 transmitted = specularScale * prefilteredAlong(position, -view,
                                                        transmissionRoughness(m.roughness, m.ior),
                                                        s.terms);
    if (frame.viewport.w > 0.5)
      transmitted = behindSurface(transmissionFrameTexel(position, n, view, m), transmitted);
    color += belowScale * transmissionRadiance(m, look.NoV, dfg.xy, transmitted, s);
  }
  // The sheen chain has the specular chain's levels and mapping; it is read at the normal
  // (src/render/renderer.cpp says why).
  if (environment && shadeSheen) {
    float lod = specularLodForRoughness(sheenRoughness, frame.lods.x, frame.lods.y > 0.5);
    vec3 prefilteredSheen = distant * textureLod(sheenMap, n, lod).rgb;
    color += sheenRadiance(sheen.rgb, sheenE, prefilteredSheen) * m.occlusion;
  }
  color *= belowCoat;
  if (coat) {
    // The coat reads the same light as the base (probes, then the distant environment, the
    // volume's scale) at its reflection and roughness; the screen-space reflection is the base's.
    vec3 light =
        prefilteredAlong(position, coatLook.specularDirection, m.clearcoatRoughness, s.terms);
    color += clearcoatRadiance(m, coatLook.NoV, coatDfg, specularScale * light, s);
  }
  return lit + color + emissive;
}
