// The shadow maps' records and depths (view/frame.glsl) as ibl/shared/shadows.h reads them: its
// accessors over the storage buffers, and the casters' records. Where the scene transmits, the
// depths' buffer goes on with the layers' filters, four floats per texel (frame.shadows.w: the
// number of layers; 0: none). Needs view/frame.glsl.
#include "ibl/shared/shadows.h"

ShadowCaster shadowCasterAt(int light) {
  int b = 5 * light;
  ShadowCaster c;
  c.kind = int(shadowData[b].x);
  c.firstLayer = int(shadowData[b].y);
  c.layerCount = int(shadowData[b].z);
  c.size = shadowData[b].w;
  c.lightPosition = shadowData[b + 1].xyz;
  c.viewOrigin = shadowData[b + 2].xyz;
  c.viewForward = shadowData[b + 3].xyz;
  c.splits = shadowData[b + 4];
  return c;
}
ShadowLayer shadowLayerAt(int i) {
  int b = int(frame.shadows.z) + 4 * i;
  ShadowLayer l;
  l.origin = shadowData[b].xyz;
  l.perspective = int(shadowData[b].w);
  l.right = shadowData[b + 1].xyz;
  l.scale = shadowData[b + 1].w;
  l.up = shadowData[b + 2].xyz;
  l.near = shadowData[b + 2].w;
  l.forward = shadowData[b + 3].xyz;
  l.far = shadowData[b + 3].w;
  return l;
}
float shadowDepthTexel(int layer, ivec2 t) {
  int n = int(frame.shadows.x);
  ivec2 c = clamp(t, ivec2(0), ivec2(n - 1));
  return shadowDepths[(layer * n + c.y) * n + c.x];
}
vec4 shadowFilterTexel(int layer, ivec2 t) {
  uint layers = uint(frame.shadows.w);
  if (layers == 0u) return vec4(1.0);
  int n = int(frame.shadows.x);
  ivec2 c = clamp(t, ivec2(0), ivec2(n - 1));
  uint at = layers * uint(n * n) + 4u * uint((layer * n + c.y) * n + c.x);
  return vec4(shadowDepths[at], shadowDepths[at + 1u], shadowDepths[at + 2u],
              shadowDepths[at + 3u]);
}
float shadowMapSize() {
  return frame.shadows.x;
}

