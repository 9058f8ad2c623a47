// The local probes' math (ibl/shared/probes.h) against direct computation: the proxy volumes'
// exit distances, the influence fades and their composition, distance-based roughness.
#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/render/probe.hpp"

using namespace ibl;

namespace {

// The exit distance by marching along the ray (independent of the slab and quadratic forms).
float marchedExit(const ProbeVolume& v, glm::vec3 p, glm::vec3 d) {
  float last = -1.0f;
  for (int i = 0; i <= 200000; ++i) {
    const float t = static_cast<float>(i) * 1e-4f;
    if (volumeContains(v, p + t * d)) last = t;
  }
  return last;
}

}  // namespace

TEST(Probes, VolumeExitDistanceAgainstMarching) {
  const ProbeVolume box =
      boxVolume({-1.0f, 0.0f, -2.0f}, {2.0f, 1.5f, 1.0f}, {10.0f, 35.0f, -20.0f});
  const ProbeVolume sphere = sphereVolume({0.5f, 0.5f, 0.0f}, 1.3f);
  const glm::vec3 inside(0.3f, 0.6f, -0.2f);
  for (const ProbeVolume& v : {box, sphere})
    for (glm::vec3 d : {glm::vec3(1, 0, 0), glm::vec3(0.3f, -0.8f, 0.5f),
                        glm::vec3(-0.2f, 0.1f, -1.0f), glm::vec3(0, 1, 0)}) {
      d = glm::normalize(d);
      EXPECT_NEAR(shared::volumeExitDistance(v, inside, d), marchedExit(v, inside, d), 2e-4f)
          << "shape " << v.shape << " d " << d.x << "," << d.y << "," << d.z;
    }
  // Outside and looking away: no exit ahead.
  EXPECT_LT(shared::volumeExitDistance(sphere, {5.0f, 0.5f, 0.0f}, {1.0f, 0.0f, 0.0f}), 0.0f);
  EXPECT_LT(shared::volumeExitDistance(box, {9.0f, 9.0f, 9.0f}, glm::normalize(glm::vec3(1.0f))),
            0.0f);
}

TEST(Probes, InfluenceFadesFromTheInnerVolumeToTheBorder) {
  const ProbeVolume box = boxVolume({-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f});
  const float fade = 0.4f;
  EXPECT_FLOAT_EQ(shared::influenceWeight(box, fade, {0.5f, 0.0f, 0.3f}), 1.0f);  // inner box
  EXPECT_FLOAT_EQ(shared::influenceWeight(box, fade, {1.1f, 0.0f, 0.0f}), 0.0f);  // outside
  // Halfway through the fade: smoothstep(0.5) = 0.5; a quarter in from the border: 0.15625.
  EXPECT_NEAR(shared::influenceWeight(box, fade, {0.8f, 0.0f, 0.0f}), 0.5f, 1e-5f);
  EXPECT_NEAR(shared::influenceWeight(box, fade, {0.9f, 0.0f, 0.0f}), 0.15625f, 1e-5f);
  const ProbeVolume sphere = sphereVolume({0.0f, 0.0f, 0.0f}, 2.0f);
  EXPECT_NEAR(shared::influenceWeight(sphere, 1.0f, {0.0f, 1.5f, 0.0f}), 0.5f, 1e-5f);
  // Composition: 0.5 then 1.0 fill the coverage; a third probe gets nothing.
  float coverage = 0.0f;
  const float first = shared::probeShare(0.5f, coverage);
  coverage += first;
  const float second = shared::probeShare(1.0f, coverage);
  coverage += second;
  EXPECT_FLOAT_EQ(first, 0.5f);
  EXPECT_FLOAT_EQ(second, 0.5f);
  EXPECT_FLOAT_EQ(shared::probeShare(1.0f, coverage), 0.0f);
}

TEST(Probes, DistanceBasedRoughnessFollowsTheDocument) {
  // Frostbite appendix F, worked by hand: receiver 1 from the hit, probe center 2, r = 0.4:
  // clamp(1 / 2 x 0.4, 0, 0.4) = 0.2, then lerp(0.2, 0.4, 0.4) = 0.28. Farther from the
  // receiver than from the center the scaled value clamps to r itself.
  EXPECT_NEAR(shared::distanceBasedRoughness(1.0f, 2.0f, 0.4f), 0.28f, 1e-6f);
  EXPECT_NEAR(shared::distanceBasedRoughness(3.0f, 1.0f, 0.4f), 0.4f, 1e-6f);
  EXPECT_NEAR(shared::distanceBasedRoughness(0.5f, 2.0f, 0.0f), 0.0f, 1e-6f);  // a mirror stays one
}
