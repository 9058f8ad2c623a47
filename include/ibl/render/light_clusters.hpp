#pragma once
// API: internal (may change without notice; renderer internals behind render/renderer.hpp)
// Which lights can reach which part of the view: the clustered light lists the viewer reads so
// that a pixel evaluates only the lights that reach it (ibl/shared/clusters.h holds the grid's
// arithmetic, shared with the shader). A light is left out of a cluster only where its
// contribution is exactly zero everywhere in the cluster: beyond its influence radius (the
// distance window of Frostbite section 4.7.1, `range`), outside a spot's outer cone, behind a
// one-sided disk or rect. A light without a range reaches every cluster its cone or side allows.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "ibl/render/camera.hpp"
#include "ibl/render/light.hpp"
#include "ibl/shared/clusters.h"

namespace ibl {

struct LightClusterSettings {
  int tileSize = 32;  // pixels per tile side
  int slices = 16;    // depth slices (at least 2)
};

// The lists: `ranges` holds (first, count) pairs into `indices`, one per cluster
// (shared::clusterIndex) and then one per tile (the emitters the tile's rays may meet: area
// lights and the sun, for what the camera sees of them); `indices` are positions in the lights'
// list, in increasing order within each list.
struct LightClusters {
  shared::LightClusterGrid grid{};
  std::vector<std::uint32_t> ranges;
  std::vector<std::uint32_t> indices;

  // The lights that may reach cluster c.
  std::span<const std::uint32_t> lightsOf(int cluster) const;
  // The emitters the rays of tile t may meet.
  std::span<const std::uint32_t> emittersOf(int tile) const;
};

// The grid over `camera`'s image for a scene whose geometry lies within `bounds` (min, max
// corners): its depth range is the part of the scene's bounding sphere in front of the camera.
shared::LightClusterGrid lightClusterGrid(const Camera& camera,
                                          std::pair<glm::vec3, glm::vec3> bounds,
                                          const LightClusterSettings& settings = {});

// Fills every cluster's and every tile's list for `lights` over that grid. Conservative: a point
// within the scene's bounds, seen through a pixel of a tile at a depth of a slice, gets nothing
// from a light its cluster leaves out; a ray through a pixel of a tile meets no emitter the tile
// leaves out.
LightClusters buildLightClusters(const std::vector<Light>& lights, const Camera& camera,
                                 std::pair<glm::vec3, glm::vec3> bounds,
                                 const LightClusterSettings& settings = {});

}  // namespace ibl
