#version 450
// The irradiance volume's live update in the viewer, its texels (gpu::VolumeUpdate in
// src/gpu/volume_update.cpp; updateVolume in src/render/irradiance_volume_update.cpp on the CPU).
// Two passes over an atlas held as RGBA32F texels in a storage buffer:
//   - blend (one invocation per interior texel of each switched-on probe): the frame's rays of
//     the probe weighted by the cosine (irradiance) or its kVolumeDistanceSharpness power
//     (distance moments) to the texel's direction, their mean blended into the texel with
//     hysteresis (volumeBlend);
//   - border (one invocation per atlas texel): the tiles' borders copied from the interior
//     (volumeBorderSource), and every texel written in the sampled image's format for the copy
//     into it (RGBA32F, or RGBA16F as halves clamped to 65504).
layout(local_size_x = 8, local_size_y = 8) in;

#include "ibl/shared/irradiance_volume.h"

layout(std430, binding = 0) readonly buffer Rays {
  vec4 rays[];  // volume_trace.comp's: radiance, distance
};
layout(std430, binding = 1) buffer Atlas {
  vec4 atlas[];  // row by row
};
layout(std430, binding = 2) writeonly buffer Transfer {
  uint transfer[];  // the atlas in the image's format
};
layout(std430, binding = 3) readonly buffer Probes {
  vec4 probes[];  // relocation offset, 1 when on
};

layout(push_constant) uniform Blend {
  ivec4 grid;   // probes per axis, the tiles' interior texels
  ivec4 atlas;  // width, height, rays per probe, flags (1 distances, 2 halves, 4 the border pass)
  vec4 rotation0;  // the frame's rotation by columns (the rays' directions); w: the hysteresis
  vec4 rotation1;
  vec4 rotation2;
} blend;

void blendTexel(ivec3 id) {
  int texels = blend.grid.w, probe = id.z;
  if (id.x >= texels || id.y >= texels || probe >= blend.grid.x * blend.grid.y * blend.grid.z)
    return;
  if (probes[probe].w < 0.5) return;
  bool distances = (blend.atlas.w & 1) != 0;
  vec3 n = octahedralDecode((vec2(id.xy) + 0.5) / float(texels) * 2.0 - 1.0);
  mat3 rotation = mat3(blend.rotation0.xyz, blend.rotation1.xyz, blend.rotation2.xyz);
  int count = blend.atlas.z;
  vec3 sum = vec3(0.0);
  float total = 0.0;
  for (int i = 0; i < count; ++i) {
    vec4 r = rays[probe * count + i];
    float c = dot(n, volumeRayDirection(i, count, rotation));
    if (c <= 0.0) continue;
    float w = distances ? pow(c, kVolumeDistanceSharpness) : c;
    sum += w * (distances ? vec3(r.w, r.w * r.w, 0.0) : r.rgb);
    total += w;
  }
  int perRow = blend.grid.x * blend.grid.y;
  ivec2 tile = ivec2(probe % perRow, probe / perRow) * (texels + 2);
  int at = (tile.y + 1 + id.y) * blend.atlas.x + tile.x + 1 + id.x;
  atlas[at] = vec4(volumeBlend(atlas[at].rgb, sum, total, blend.rotation0.w), 1.0);
}

void borderTexel(ivec2 t) {
  if (t.x >= blend.atlas.x || t.y >= blend.atlas.y) return;
  int side = blend.grid.w + 2;
  ivec2 inTile = t % side;
  int at = t.y * blend.atlas.x + t.x;
  ivec2 source = volumeBorderSource(inTile, blend.grid.w);
  vec4 value = atlas[(t.y - inTile.y + source.y) * blend.atlas.x + t.x - inTile.x + source.x];
  if (source != inTile) atlas[at] = value;
  if ((blend.atlas.w & 2) != 0) {
    vec4 h = clamp(value, vec4(-65504.0), vec4(65504.0));
    transfer[2 * at] = packHalf2x16(h.xy);
    transfer[2 * at + 1] = packHalf2x16(h.zw);
  } else {
    for (int c = 0; c < 4; ++c) transfer[4 * at + c] = floatBitsToUint(value[c]);
  }
}

void main() {
  if ((blend.atlas.w & 4) != 0)
    borderTexel(ivec2(gl_GlobalInvocationID.xy));
  else
    blendTexel(ivec3(gl_GlobalInvocationID));
}
