#version 450
#extension GL_EXT_samplerless_texture_functions : require
// The irradiance volume's live update in the viewer, its rays (gpu::VolumeUpdate in
// src/gpu/volume_update.cpp; updateVolume in src/render/irradiance_volume_update.cpp on the CPU):
// ray i of probe p leaves along volumeRayDirection(i, rays, the frame's rotation), meets the
// scene in the reference's BVH (render/scene_buffers.glsl, set 1), and takes the radiance the
// hit sends back: the split sum's diffuse of the distant environment and of the volume as it
// stood before this frame (so that bounces add up over frames), and the lights' with their
// visibility traced. Its result: (radiance, distance to the hit, at most `farthest`).
layout(local_size_x = 64) in;

#include "ibl/shared/color.h"
#include "view/frame.glsl"
#include "view/shading.glsl"
#define SCENE_SET 1
#include "render/scene_buffers.glsl"
#include "ibl/shared/light_sampling.h"
#include "ibl/shared/path_sampler.h"

const int kVolumeRaysBinding = 5;  // in the scene's set, after scene_buffers.glsl's five
layout(std430, set = SCENE_SET, binding = kVolumeRaysBinding) writeonly buffer Rays {
  vec4 rays[];  // per probe, its rays in turn: radiance, distance
};

layout(push_constant) uniform Update {
  vec4 rotation0;  // the frame's rotation by columns; w of the first: the farthest distance
  vec4 rotation1;
  vec4 rotation2;
  ivec4 counts;  // rays per probe, probes, flags (1 metals as diffuse, 2 the scene transmits)
  ivec4 keys;    // the capture's seed, the frame
} update;

const float kFar = 1e30;

// The material of a hit as the split sum's formulas take it (splitSumMaterial in
// src/render/renderer.cpp), without ambient occlusion or emission.
SplitSumMaterial hitMaterial(Surface p) {
  SplitSumMaterial m;
  m.baseColor = p.baseColor;
  m.metallic = p.metallic;
  m.roughness = p.roughness;
  m.occlusion = 1.0;
  m.emissive = vec3(0.0);
  m.ior = p.ior;
  m.specular = p.specular;
  m.specularColor = p.specularColor;
  m.clearcoat = p.clearcoat;
  m.clearcoatRoughness = p.clearcoatRoughness;
  m.clearcoatNormal = p.clearcoatNormal;
  m.iridescence = p.iridescence;
  m.iridescenceIor = p.iridescenceIor;
  m.iridescenceThickness = p.iridescenceThickness;
  m.anisotropy = p.anisotropy;
  m.anisotropyTangent = p.anisotropyTangent;
  m.transmission = p.transmission;
  m.thickness = p.volume ? p.thickness : 0.0;
  m.attenuation = p.attenuation;
  return m;
}

// The first surface that transmits nothing from `origin` along unit `dir` within `reach` (t from
// `origin`; found false: none), and in `passed` the share of light that the surfaces that
// transmit before it let through in a straight line (straightTransmittance in
// src/render/shadows.cpp): surfaceShadowTransmittance at each, and Beer-Lambert over the chords of
// the volumes (summed as -sigma in + sigma out; to the opaque hit, or the end of the segment, for
// the volumes entered and not left).
SceneHit firstOpaqueHitThrough(vec3 origin, vec3 dir, float reach, out vec3 passed) {
  passed = vec3(1.0);
  vec3 opticalDepth = vec3(0.0), inside = vec3(0.0);
  float travelled = 0.0;
  vec3 from = origin;
  SceneHit opaque = SceneHit(false, reach, false, 0u, 0u, 0.0, 0.0);
  for (int surfaces = 0; surfaces < 256; ++surfaces) {
    SceneHit hit = intersectScene(from, dir, reach - travelled, false);
    if (!hit.found) break;
    Surface s = surfaceAt(hit, from, dir);
    float at = travelled + hit.t;
    if (s.transmission <= 0.0) {
      opaque = hit;
      opaque.t = at;
      break;
    }
    passed *= surfaceShadowTransmittance(hitMaterial(s), dot(s.faceNormal, dir));
    if (s.volume) {
      opticalDepth += (s.frontFace ? -at : at) * s.attenuation;
      inside = max(inside + (s.frontFace ? 1.0 : -1.0) * s.attenuation, vec3(0.0));
    }
    float step = hit.t + 1e-4 * max(1.0, length(s.position));
    from += step * dir;
    travelled += step;
  }
  if (opaque.found || reach < kFar) opticalDepth += inside * opaque.t;
  passed *= exp(-max(opticalDepth, vec3(0.0)));
  return opaque;
}

// The share of light that crosses from `origin` along unit `dir` for `reach` in a straight line:
// 0 behind a surface that transmits nothing.
vec3 straightTransmittance(vec3 origin, vec3 dir, float reach) {
  vec3 passed;
  return firstOpaqueHitThrough(origin, dir, reach, passed).found ? vec3(0.0) : passed;
}

// The share of light l's irradiance that reaches p, per channel (rayTracedVisibility in
// src/render/shadows.cpp with one sample).
vec3 tracedVisibility(ShadingLight l, vec3 p, vec3 n, vec2 xi) {
  vec3 direction;
  float distance;
  if (l.type == kLightPoint || l.type == kLightSpot) {
    vec3 d = l.position - p;
    distance = length(d);
    direction = d / distance;
  } else {
    AreaLightSample s = sampleAreaLight(l, p, xi);
    if (!(s.pdf > 0.0) || !(luminance(s.radiance) * abs(dot(n, s.direction)) > 0.0))
      return vec3(1.0);
    direction = s.direction;
    distance = s.distance;
  }
  vec3 origin = p + (dot(n, direction) >= 0.0 ? n : -n) * (1e-4 * max(1.0, length(p)));
  float reach = distance < kSunDistance ? distance * (1.0 - 1e-4) : kFar;
  if ((update.counts.z & 2) != 0) return straightTransmittance(origin, direction, reach);
  return vec3(occluded(origin, direction, reach) ? 0.0 : 1.0);
}

// The radiance a hit p sends back along `view` (shadeSplitSum with --only diffuse plus
// shadeLightsRealTime, their visibility traced, in src/render/renderer.cpp).
vec3 shadeHit(Surface p, vec3 view, inout PathSampler numbers) {
  SplitSumSwitches s = frameSwitches();
  s.terms = 1;  // diffuse
  SplitSumMaterial m = hitMaterial(p);
  m.anisotropy = 0.0;  // the diffuse alone (the transmission: the diffuse's share)
  // What a clear coat lets through of the diffuse below it (its own lobe is specular).
  float belowCoat =
      p.clearcoat > 0.0 ? 1.0 - clearcoatWeight(p.clearcoat, dot(p.clearcoatNormal, view)) : 1.0;
  vec3 n = p.normal;
  SplitSumLookup look = splitSumLookup(n, view, m.roughness, s);
  vec3 dfg = textureLod(dfgLut, vec2(look.NoV, m.roughness), 0.0).rgb;
  vec3 irradiance = frame.lods.w >= 0.5 ? distantIrradiance(look.diffuseDirection) : vec3(0.0);
  VolumeGrid g = frameVolumeGrid();
  float cover = volumeCoverage(g, p.position);
  if (cover > 0.0)
    irradiance = mix(irradiance, volumeLookup(g, p.position, n, view, look.diffuseDirection), cover);
  vec3 color = splitSumRadiance(m, look.NoV, dfg, vec3(0.0), irradiance, s);
  if (p.sheenColor != vec3(0.0)) {
    float e = textureLod(sheenDfgLut, vec2(look.NoV, max(p.sheenRoughness, kMinSheenRoughness)),
                         0.0).r;
    color *= sheenAlbedoScaling(p.sheenColor, e);
  }
  color *= belowCoat;
  vec4 ltc = s.ltcAreaLights ? ltcTableEntry(m.roughness, look.NoV) : vec4(1.0, 0.0, 0.0, 1.0);
  for (int i = 0; i < frame.models.w; ++i) {
    LightRecord record = lightRecordAt(i);
    ShadingLight l = unpackLight(record);
    vec3 visible = tracedVisibility(l, p.position, n, pathUniform2(numbers));
    if (visible == vec3(0.0)) continue;
    LightIncidence inc = lightIncidence(l, p.position, n, view, m.roughness, s, ltc);
    vec3 profile = visible * iesProfileFactor(l, lightRecordProfile(record),
                                              normalize(p.position - l.position));
    color += l.color * (profile * belowCoat) * lightRadiance(m, n, view, inc, dfg.xy, s);
  }
  return color + p.emissive;
}

void main() {
  int ray = int(gl_GlobalInvocationID.x), probe = int(gl_GlobalInvocationID.y);
  int count = update.counts.x;
  if (ray >= count || probe >= update.counts.y) return;
  vec4 record = volumeProbeData[probe];  // relocation offset, 1 when on
  if (record.w < 0.5) return;
  VolumeGrid g = frameVolumeGrid();
  vec3 origin = volumeGridPosition(g, probe) + record.xyz;
  mat3 rotation = mat3(update.rotation0.xyz, update.rotation1.xyz, update.rotation2.xyz);
  vec3 dir = volumeRayDirection(ray, count, rotation);
  float farthest = update.rotation0.w;
  uint slot = uint(probe * count + ray);
  // Through the surfaces that transmit, as the shadows see (updateVolume in
  // src/render/irradiance_volume_update.cpp): what lies behind them, tinted.
  vec3 through = vec3(1.0);
  SceneHit hit = (update.counts.z & 2) != 0 ? firstOpaqueHitThrough(origin, dir, kFar, through)
                                            : intersectScene(origin, dir, kFar, false);
  if (!hit.found) {
    vec3 sky = frame.lods.w >= 0.5 ? textureLod(sourceMap, dir, 0.0).rgb : vec3(0.0);
    rays[slot] = vec4(through * sky, farthest);
    return;
  }
  Surface p = surfaceAt(hit, origin, dir);
  if ((update.counts.z & 1) != 0) p = metalAsDiffuse(p);
  PathSampler numbers = pathSamplerAt(pathSamplerKey(uint(update.keys.x), uint(update.keys.y), slot, 0u), 0u);
  rays[slot] = vec4(through * shadeHit(p, -dir, numbers), min(hit.t, farthest));
}
