#version 450
// Split-sum shading of the viewer's meshes: the material's textures and normal map as in
// surfaceAt (src/render/ray_tracer.cpp), through ibl/shared/material.h, then shadeSplitSum
// (view/shading.glsl), with the sheen layer of KHR_materials_sheen.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "ibl/shared/color.h"
#include "view/frame.glsl"
#include "view/shading.glsl"
#include "ibl/shared/buffer_views.h"
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec4 worldTangent;
layout(location = 3) in vec2 texCoord0;
layout(location = 4) in vec2 texCoord1;
layout(location = 5) in vec4 vertexColor;
layout(location = 0) out vec4 outColor;
#include "view/material.glsl"
#include "view/surface.glsl"

// The sun's shadow cascade at `position` (-1: beyond the last, or no light with cascades).
int shadowCascadeAt(vec3 position) {
  if (!kCastShadows) return -1;
  for (int i = 0; i < frame.models.w; ++i) {
    ShadowCaster c = shadowCasterAt(i);
    if (c.kind == kShadowCascades) {
      int cascade = shadowCascadeIndex(dot(position - c.viewOrigin, c.viewForward), c.splits,
                                       c.layerCount);
      return cascade < c.layerCount ? cascade : -1;
    }
  }
  return -1;
}

// What the buffer view `view` (kBuffer*, not kBufferShaded) shows of this fragment's surface:
// materialOcclusion is the occlusion texture's, screenOcclusion GTAO's (1: none), reflection the
// screen-space reflection (0: none).
vec3 bufferViewColor(int view, ShadedSurface s, float materialOcclusion, float screenOcclusion,
                     vec4 reflection) {
  SplitSumMaterial m = s.material;
  float shade = 0.25 + 0.75 * max(dot(s.normal, s.view), 0.0);  // legible shapes under colors
  if (view == kBufferBaseColor) return m.baseColor;
  if (view == kBufferRoughness) return grayOfValue(m.roughness);
  if (view == kBufferMetallic) return grayOfValue(m.metallic);
  if (view == kBufferNormals) return srgbToLinear(s.normal * 0.5 + 0.5);
  if (view == kBufferMaterialOcclusion) return grayOfValue(materialOcclusion);
  if (view == kBufferScreenOcclusion) return grayOfValue(screenOcclusion);
  if (view == kBufferShadowCascades) return cascadeColor(shadowCascadeAt(s.position), shade);
  if (view == kBufferLightClusters) {
    float count = frame.models.w > 0 ? float(clusterLights(gl_FragCoord.xy, s.position).y) : 0.0;
    return heatMapColor(count / float(kBufferHeatMapLights));
  }
  if (view == kBufferReflectionHits) return heatMapColor(reflection.a) * shade;
  if (view == kBufferProbeInfluence) {
    vec3 prefiltered, irradiance;
    float coverage = frame.probes.x > 0.0
                         ? localProbes(s.position, s.normal, s.normal, 1.0, 0, prefiltered,
                                       irradiance).y
                         : 0.0;
    return heatMapColor(coverage) * shade;
  }
  if (view == kBufferVolumeInfluence) {
    float coverage =
        frame.volumeTexels.z != 0 ? volumeCoverage(frameVolumeGrid(), s.position) : 0.0;
    return heatMapColor(coverage) * shade;
  }
  // An unlit material (KHR_materials_unlit: its color moved to the emission) is not shaded, so
  // not validated.
  int verdict = material.alpha.w != 0.0
                    ? kValidationPlausible
                    : materialValidation(m.baseColor, m.metallic, s.metallicChange, m.emissive);
  return validationColor(verdict, m.baseColor) * shade;
}

void main() {
  ShadedSurface surface = fragmentSurface(frame.models.z, frame.shading.w != 0);
  float materialOcclusion = surface.material.occlusion, screenOcclusionValue = 1.0;
  vec3 bentNormal = vec3(0.0);
  if (frame.ambientOcclusion.z > 0.0 && draw.scenePass != 3) {
    // Screen-space ambient occlusion (view/gtao.frag) at this pixel: min with the material's
    // (Lagarde & de Rousiers 2014, 4.10.3), and the bent normal for the irradiance. Not in the
    // opaque frame behind transmissive surfaces, whose pixels the view buffers give to them.
    vec4 ao = texelFetch(screenOcclusion, ivec2(gl_FragCoord.xy), 0);
    screenOcclusionValue = ao.x;
    surface.material.occlusion = min(surface.material.occlusion, ao.x);
    // The pixel's bent normal, unless it is another surface's (an edge, with multisampling).
    if (dot(ao.yzw, surface.normal) > 0.0) bentNormal = ao.yzw;
  }
  // The screen-space reflection (view/ssr.frag), in the second pass of a frame that has them.
  vec4 reflection = draw.scenePass == 2
                        ? texelFetch(screenReflection, ivec2(gl_FragCoord.xy), 0)
                        : vec4(0.0);
  // A buffer view, in the frame's last pass (not the lit frame before the reflections, nor the
  // opaque frame behind transmissive surfaces, which it shows through).
  if (frame.bufferView.x != kBufferShaded && (draw.scenePass == 0 || draw.scenePass == 2)) {
    outColor = vec4(bufferViewColor(frame.bufferView.x, surface, materialOcclusion,
                                    screenOcclusionValue, reflection),
                    1.0);
    return;
  }
  vec3 color = shadeSplitSum(surface.position, gl_FragCoord.xy, surface.normal, surface.view,
                             surface.material, surface.sheen, bentNormal, reflection);
  // An area light between the camera and the surface is what the pixel sees; not in the lit
  // frame of the screen-space reflections, whose rays meet the surfaces of the view buffers, nor
  // in the opaque frame behind transmissive surfaces (lit as that one).
  Ray center = primaryRay(gl_FragCoord.xy);
  vec3 emitted;
  bool isSurface;
  if ((draw.scenePass == 0 || draw.scenePass == 2) &&
      nearestEmitter(center, gl_FragCoord.xy,
                     dot(surface.position - center.origin, center.direction), emitted, isSurface))
    color = emitted;
  outColor = vec4(color, 1.0);
}
