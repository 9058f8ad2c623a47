// The lights' real-time shadows (render/shadows.hpp, ibl/shared/shadows.h) against the
// reference's ray-traced visibility: each light type's shadow where the reference has it, no
// acne on lit surfaces, cascades that hold the points they are chosen for, penumbrae as wide as
// the light makes them.
#include <cmath>

#include <gtest/gtest.h>

#include "ibl/render/shadows.hpp"
#include "support/shadow_scenes.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

const BlackBake& black() {
  static const BlackBake b = blackBake();
  return b;
}

RenderOptions shadowOptions(ShadowMode mode, int mapSize = 512) {
  RenderOptions o;
  o.realTimeShadows = mode;
  o.shadowSettings.mapSize = mapSize;
  o.spp = 1;
  return o;
}

TEST(Shadows, Explore) {
  for (LightType type : {LightType::Point, LightType::Spot, LightType::Sun, LightType::Sphere,
                         LightType::Disk, LightType::Tube, LightType::Rect}) {
    const Scene scene = blockersOverFloor(shadowStudyLight(type));
    const Camera camera = floorCamera(64);
    for (ShadowMode mode : {ShadowMode::Map, ShadowMode::Ray}) {
      const ShadowStudy s = renderShadowStudy(scene, camera, black(), shadowOptions(mode), 64);
      const ShadowError e = compareShadows(s);
      std::printf("%-6s %-4s compared %5.0f shadowed %5.3f mismatch %6.4f median dv %6.4f rel %6.4f\n",
                  std::string(lightTypeName(type)).c_str(), std::string(shadowModeName(mode)).c_str(),
                  e.compared, e.referenceShadowed, e.stateMismatch, e.medianVisibility, e.relative);
    }
  }
}

}  // namespace
