// API: internal (may change without notice; math shared with the shaders)
// Clustered light culling (Olsson, Billeter and Assarsson 2012, "Clustered Deferred and Forward
// Shading"; the clustered forward renderer of Persson and Olsson 2013): the view is cut into
// tiles of pixels and, along the view depth, into slices; each cluster (a tile's slice) lists
// the lights that may reach a point inside it, each tile the emitters its pixels' rays may meet.
// The grid's arithmetic is written once here: the CPU fills the lists (src/render/
// light_clusters.cpp), the viewer's fragment shader finds its cluster with the same functions.
// C++ and GLSL (see lang.h).
//
// Depth is the distance along the camera's forward axis from the camera's plane. Slice 0 holds
// everything nearer than `near`; slices 1 to slices - 1 split [near, far] exponentially in
// perspective (each as deep as it is wide, Olsson et al. 2012 section 4.2) and uniformly for an
// orthographic camera; depths past `far` belong to the last slice.
#ifndef IBL_SHARED_CLUSTERS_H
#define IBL_SHARED_CLUSTERS_H
#include "ibl/shared/lang.h"

IBL_BEGIN

struct LightClusterGrid {
  int tileSize;        // pixels per tile side
  int tilesX, tilesY;  // tiles across and down the image (the last ones may be partial)
  int slices;          // depth slices, at least 2
  float near, far;     // the depth range sliced (0 < near < far in perspective)
  int perspective;     // 1: exponential slices; 0: uniform (orthographic)
};

// Where depth z falls in the sliced range, 0 at near and 1 at far (unclamped).
IBL_FN float clusterDepthFraction(LightClusterGrid g, float z) {
  if (g.perspective != 0) return log(max(z, 1e-30f) / g.near) / log(g.far / g.near);
  return (z - g.near) / (g.far - g.near);
}

// The slice that holds depth z.
IBL_FN int clusterSlice(LightClusterGrid g, float z) {
  if (z < g.near) return 0;
  float k = 1.0f + floor(clusterDepthFraction(g, z) * float(g.slices - 1));
  return int(clamp(k, 1.0f, float(g.slices - 1)));  // clamped before the conversion
}

// The depth where slice k (1 to slices - 1) begins: near times (far / near)^t in perspective,
// near + t (far - near) otherwise, t = (k - 1) / (slices - 1). Slice k ends where k + 1 begins.
IBL_FN float clusterSliceStart(LightClusterGrid g, int k) {
  float t = float(k - 1) / float(g.slices - 1);
  if (g.perspective != 0) return g.near * pow(g.far / g.near, t);
  return mix(g.near, g.far, t);
}

// The tile of a framebuffer point (pixels, (0, 0) the top-left corner), as one index.
IBL_FN int clusterTile(LightClusterGrid g, vec2 pixel) {
  int tx = clamp(int(floor(pixel.x)) / g.tileSize, 0, g.tilesX - 1);
  int ty = clamp(int(floor(pixel.y)) / g.tileSize, 0, g.tilesY - 1);
  return ty * g.tilesX + tx;
}

// The cluster of a point seen at framebuffer point `pixel` at depth z: slice after slice, tiles
// row by row within a slice.
IBL_FN int clusterIndex(LightClusterGrid g, vec2 pixel, float z) {
  return clusterSlice(g, z) * g.tilesX * g.tilesY + clusterTile(g, pixel);
}

// Clusters in the grid (the tiles' emitter lists follow them in the lists' table).
IBL_FN int clusterCount(LightClusterGrid g) {
  return g.tilesX * g.tilesY * g.slices;
}

IBL_END

#endif
