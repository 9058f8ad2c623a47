#pragma once
// Helpers of the physical sky's tests.
#include "ibl/env/sky.hpp"

namespace ibl::test {

// The default atmosphere with the sun at `elevation` degrees, `azimuth` degrees from north.
inline SkyParameters sunAt(float elevation, float azimuth = 180.0f) {
  SkyParameters p;
  p.sunElevation = elevation;
  p.sunAzimuth = azimuth;
  return p;
}

}  // namespace ibl::test
