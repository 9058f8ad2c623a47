// The light clusters' grid (ibl/shared/clusters.h): its depth slices against their closed forms,
// and the tiles' and slices' order.
#include <cmath>

#include <gtest/gtest.h>

#include "ibl/shared/clusters.h"

using namespace ibl;

// Slice k begins at near (far / near)^((k - 1) / (S - 1)) in perspective, evenly between near and
// far orthographic; a depth just inside a slice's bounds is in that slice.
TEST(LightClusters, SlicesFollowTheirClosedForm) {
  for (int perspective : {1, 0}) {
    shared::LightClusterGrid g{};
    g.tileSize = 16;
    g.tilesX = 4;
    g.tilesY = 3;
    g.slices = 9;
    g.near = 0.5f;
    g.far = 128.0f;
    g.perspective = perspective;
    for (int k = 1; k < g.slices; ++k) {
      const double t = static_cast<double>(k - 1) / (g.slices - 1);
      const double expected = perspective ? 0.5 * std::pow(256.0, t) : 0.5 + t * 127.5;
      EXPECT_NEAR(shared::clusterSliceStart(g, k), expected, 1e-5 * expected) << k;
      EXPECT_EQ(shared::clusterSlice(g, static_cast<float>(expected * 1.0001)), k);
      if (k > 1) {
        EXPECT_EQ(shared::clusterSlice(g, static_cast<float>(expected * 0.9999)), k - 1);
      }
    }
    EXPECT_EQ(shared::clusterSlice(g, 0.25f), 0);
    EXPECT_EQ(shared::clusterSlice(g, 1e4f), g.slices - 1);
    // Tiles row by row, slices after one another.
    EXPECT_EQ(shared::clusterIndex(g, {17.0f, 33.0f}, 0.1f), 2 * 4 + 1);
    EXPECT_EQ(shared::clusterIndex(g, {63.9f, 0.0f}, 1e4f), 8 * 12 + 3);
  }
}

// Every light that gives anything at a point of the view is in the point's cluster's list.
