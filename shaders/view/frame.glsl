// The per-frame inputs of the viewer's shaders: camera, shading switches and the baked
// environment. The block mirrors FrameUniforms in src/gpu/frame_layout.hpp (std140); the
// bindings are named in ibl/shared/view_bindings.h.
#include "ibl/shared/view_bindings.h"

layout(std140, set = 0, binding = kFrameUniforms) uniform Frame {
  mat4 viewProjection;
  vec4 cameraPosition;  // w: 1 perspective, 0 orthographic
  vec4 cameraForward;   // unit
  vec4 cameraRight;     // scaled by aspect * tan(fov / 2), orthographic: by the half width
  vec4 cameraUp;        // scaled by tan(fov / 2), orthographic: by the half height
  vec4 viewport;        // width, height, area lights (1 LTC, 0 Frostbite's), 1 the transmission's
                        // opaque frame is drawn (transmissionFrame)
  vec4 background;      // rgb; w: 1 the environment, 0 this color
  vec4 lods;            // specular levels - 1, 1 for the Frostbite roughness mapping, skybox lod,
                        // 1 lit by the environment (0: --env none)
  ivec4 terms;          // only (0 all, 1 diffuse, 2 specular, 3 sheen), multiple scattering, dominant
                        // directions, specular occlusion
  ivec4 models;         // diffuse (0 Disney, 1 Lambert), irradiance (0 cube, 1 SH9), samples
                        // per pixel at the standard locations (0: unknown locations), lights
  vec4 probes;          // local probes: count, their specular levels - 1, flags (1 parallax
                        // correction, 2 distance-based roughness, 4 Frostbite's roughness mapping)
  vec4 sh[9];           // radiance SH9 times the cosine lobe's A_l / pi: irradiance / pi
  ivec4 shading;        // the sheen lobe's visibility (kSheenVisibilityCharlie, ...Neubelt),
                        // specular micro-occlusion (1 on), multiple-bounce occlusion (1 on),
                        // specular antialiasing (1 on)
  vec4 shadows;         // the lights' shadow maps: texels per side, 1 when they are on, the first
                        // layer's record in shadowData, the layers whose filters follow the
                        // depths in shadowDepths (0: nothing transmits)
  ivec4 clusterGrid;    // the light clusters (ibl/shared/clusters.h): tile size in pixels, tiles
                        // across, tiles down, depth slices
  vec4 clusterDepths;   // near, far, 1 perspective (exponential slices), 0 orthographic
  vec4 ambientOcclusion;  // screen-space (ibl/shared/ambient_occlusion.h): radius, falloff,
                          // slices (0: off), steps
  vec4 projection;      // ScreenProjection's scale (x, y), perspective (1) or orthographic (0)
  vec4 reflectionMarch;  // screen-space reflections (ibl/shared/screen_space_reflections.h):
                         // max distance, thickness, stride, max steps
  vec4 reflectionLobe;   // rays per pixel, roughness fade start and end, edge fade
  vec4 volumeOrigin;     // the irradiance volume's VolumeGrid (ibl/shared/irradiance_volume.h):
                         // origin, normal bias
  vec4 volumeSpacing;    // spacing, view bias
  ivec4 volumeCounts;    // probes per axis, rules (kVolume* bits)
  ivec4 volumeTexels;    // the irradiance and distance tiles' interiors, 1 with a volume (0: none)
  ivec4 bufferView;      // the buffer the scene pass shows (kBuffer*, ibl/shared/buffer_views.h;
                         // 0: the shading), 1 every material drawn as clay, 0, 0
  vec4 jitter;           // the projection's sub-pixel shift in pixels (temporal antialiasing), 0, 0
} frame;
layout(set = 0, binding = kFrameSpecularMap) uniform samplerCube specularMap;
layout(set = 0, binding = kFrameIrradianceMap) uniform samplerCube irradianceMap;
layout(set = 0, binding = kFrameDfgLut) uniform sampler2D dfgLut;
layout(set = 0, binding = kFrameSourceMap) uniform samplerCube sourceMap;
// The scene's lights (lightsBuffer in src/gpu/scene_upload.cpp), a LightRecord each: five vec4
// as ibl/shared/light_record.h lays them out (the IES profile: its index in iesTable, -1 for none).
layout(std430, set = 0, binding = kFrameLights) readonly buffer Lights {
  vec4 lightData[];
};
// The GGX table of linearly transformed cosines (src/render/ltc_table.inc), read by texelFetch.
// This and the other images read only by texelFetch are sampled images without a sampler
// (GL_EXT_samplerless_texture_functions, which each shader that includes this file enables):
// samplers are few per stage (lavapipe allows 32: the frame's and a material's together).
layout(set = 0, binding = kFrameLtcTable) uniform texture2D ltcTable;
// The lights' IES profiles, kIesTableRows rows each (ibl/shared/light_record.h), read by texelFetch.
layout(set = 0, binding = kFrameIesTable) uniform texture2D iesTable;

struct Ray {
  vec3 origin, direction;
};

// The primary ray through framebuffer point p (Camera::generateRay) of the frame's image, which
// the jitter shifts.
Ray primaryRay(vec2 p) {
  p -= frame.jitter.xy;
  float x = 2.0 * p.x / frame.viewport.x - 1.0;
  float y = 1.0 - 2.0 * p.y / frame.viewport.y;
  if (frame.cameraPosition.w == 0.0)
    return Ray(frame.cameraPosition.xyz + x * frame.cameraRight.xyz + y * frame.cameraUp.xyz,
               frame.cameraForward.xyz);
  return Ray(frame.cameraPosition.xyz,
             normalize(frame.cameraForward.xyz + x * frame.cameraRight.xyz + y * frame.cameraUp.xyz));
}
// Distance along r to the sphere's nearest point in front of the origin, or -1.
float intersectSphere(Ray r, vec4 sphere) {
  vec3 oc = r.origin - sphere.xyz;
  float b = dot(oc, r.direction);
  float c = dot(oc, oc) - sphere.w * sphere.w;
  float disc = b * b - c;
  if (disc < 0.0) return -1.0;
  float s = sqrt(disc);
  return -b - s >= 0.0 ? -b - s : (-b + s >= 0.0 ? -b + s : -1.0);
}

// The local probes, smallest influence first (uploadProbes in src/gpu/scene_upload.cpp), 11
// vec4 each: (capture point, has a proxy), proxy (center and shape, half extent, the three
// columns of its world-to-local rotation), influence (the same; the half extent's w: the fade).
layout(std430, set = 0, binding = kFrameProbes) readonly buffer Probes {
  vec4 probeData[];
};
layout(set = 0, binding = kFrameProbeSpecularMaps) uniform samplerCubeArray probeSpecularMaps;
layout(set = 0, binding = kFrameProbeIrradianceMaps) uniform samplerCubeArray probeIrradianceMaps;
// The sheen (Charlie) prefiltered cube, with the specular cube's levels and mapping, and its
// table (R: the lobe's albedo E at (n.v, sheen roughness)); 1 x 1 black when the bake has none.
layout(set = 0, binding = kFrameSheenMap) uniform samplerCube sheenMap;
layout(set = 0, binding = kFrameSheenDfgLut) uniform sampler2D sheenDfgLut;
// The table of the Charlie microsurface's projected area (ibl/shared/charlie_table.h), read by
// the sheen's visibility (charlieTableEntry in view/shading.glsl).
layout(std430, set = 0, binding = kFrameCharlieTable) readonly buffer CharlieTable {
  float charlieTable[];
};
// The lights' shadows (ShadowPass in src/gpu/shadow_pass.cpp): per light a caster, five
// vec4 ((kind, first layer, layer count, size), light position, view origin, view forward,
// cascade splits), then per layer four ((origin, perspective), (right, scale), (up, near),
// (forward, far)); and the layers' depths, layer after layer in rows (ibl/shared/shadows.h).
layout(std430, set = 0, binding = kFrameShadowRecords) readonly buffer ShadowRecords {
  vec4 shadowData[];
};
layout(std430, set = 0, binding = kFrameShadowDepths) readonly buffer ShadowDepths {
  float shadowDepths[];
};
// The clustered light lists (buildLightClusters in src/render/light_clusters.cpp): (first,
// count) per cluster (clusterIndex in ibl/shared/clusters.h), then per tile for its emitters,
// each `first` the position in this array of a run of light indices.
layout(std430, set = 0, binding = kFrameLightClusters) readonly buffer LightClusters {
  uint clusterData[];
};
// The irradiance volume (VolumeUpload in src/gpu/volume_upload.cpp): its atlases (RGB the
// irradiance over pi; R, G the distance moments; the tiles as ibl/shared/irradiance_volume.h lays
// them out), read bilinearly, and per probe its relocation record (offset, 1 when on); 1 x 1
// zero stand-ins without a volume.
layout(set = 0, binding = kFrameVolumeIrradiance) uniform sampler2D volumeIrradianceAtlas;
layout(set = 0, binding = kFrameVolumeDistance) uniform sampler2D volumeDistanceAtlas;
layout(std430, set = 0, binding = kFrameVolumeProbes) readonly buffer VolumeProbes {
  vec4 volumeProbeData[];
};
// Screen-space ambient occlusion (and reflections): the view buffers (view/view_buffers.frag:
// view-space position, w 1 where a surface is; view-space normal, w the perceptual roughness) and
// the occlusion (view/gtao.frag: visibility, bent normal in world space), one texel per pixel,
// read by texelFetch; 1 x 1 stand-ins when off.
layout(set = 0, binding = kFrameViewPositions) uniform texture2D viewPositions;
layout(set = 0, binding = kFrameViewNormals) uniform texture2D viewNormals;
layout(set = 0, binding = kFrameScreenOcclusion) uniform sampler2D screenOcclusion;
// Screen-space reflections: the reflection (view/ssr.frag: premultiplied radiance, the lobe's
// share the screen holds), read by the scene's second pass, and the lit frame (the scene's first
// pass) whose radiance the rays' hits take; one texel per pixel, read by texelFetch; 1 x 1 zero
// stand-ins when off.
layout(set = 0, binding = kFrameScreenReflection) uniform sampler2D screenReflection;
layout(set = 0, binding = kFrameLitFrame) uniform sampler2D litFrame;
// The reflection as traced (view/ssr.frag), before the resolve (view/ssr_resolve.frag) shares it
// between neighbors.
layout(set = 0, binding = kFrameTracedReflection) uniform sampler2D tracedReflection;
// KHR_materials_transmission: the opaque frame behind transmissive surfaces (src/gpu/
// transmission_pass.cpp: premultiplied radiance, coverage), its chain read through a trilinear
// sampler where frame.viewport.w is 1; a 1 x 1 zero stand-in when the scene transmits nothing.
layout(set = 0, binding = kFrameTransmissionFrame) uniform sampler2D transmissionFrame;
