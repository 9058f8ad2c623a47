// The irradiance volume's lookup (lookupVolume in src/render/irradiance_volume.cpp): the loop of
// ibl/shared/irradiance_volume.h over the eight probes around a point, its two reads bilinear
// from the atlases. Needs view/frame.glsl.
#include "ibl/shared/irradiance_volume.h"

// The volume's grid from the frame's uniforms (packFrameUniforms in src/gpu/frame_layout.cpp).
VolumeGrid frameVolumeGrid() {
  VolumeGrid g;
  g.origin = frame.volumeOrigin.xyz;
  g.spacing = frame.volumeSpacing.xyz;
  g.counts = frame.volumeCounts.xyz;
  g.normalBias = frame.volumeOrigin.w;
  g.viewBias = frame.volumeSpacing.w;
  g.irradianceTexels = frame.volumeTexels.x;
  g.distanceTexels = frame.volumeTexels.y;
  g.rules = frame.volumeCounts.w;
  return g;
}

// An atlas read bilinearly at a point in texels (volumeAtlasTexel; sampleVolumeAtlas on the
// CPU); level 0 alone, so no derivatives are needed inside the loop.
vec3 volumeAtlasAt(sampler2D atlas, vec2 texel) {
  return textureLod(atlas, texel / vec2(textureSize(atlas, 0)), 0.0).rgb;
}

// The volume's irradiance over pi at p: unit normal n, unit v toward the viewer, the diffuse
// lookup direction d.
vec3 volumeLookup(VolumeGrid g, vec3 p, vec3 n, vec3 v, vec3 d) {
  vec3 sum = vec3(0.0);
  float total = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    int probe = volumeCornerProbe(g, p, corner);
    VolumeCorner c = volumeCorner(g, p, n, v, corner, volumeProbeData[probe]);
    if (c.weight <= 0.0) continue;
    vec2 moments = volumeAtlasAt(volumeDistanceAtlas,
                                 volumeAtlasTexel(g, probe, c.direction, g.distanceTexels)).xy;
    float w = volumeCornerWeight(g, c, moments);
    sum += w * volumeAtlasAt(volumeIrradianceAtlas,
                             volumeAtlasTexel(g, probe, d, g.irradianceTexels));
    total += w;
  }
  return volumeIrradiance(sum, total);
}
