// The `sky:` descriptions every command accepts where it reads an environment: parameters, a
// date and place for the sun, and the mistakes it rejects, each named in its message.
#include <string>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/env/sky.hpp"

using namespace ibl;

TEST(SkySpec, ParsesAndRejects) {
  const SkySpec s = parseSkySpec("sky:elevation=12.5,azimuth=250,turbidity=3,size=256x128");
  EXPECT_FLOAT_EQ(s.parameters.sunElevation, 12.5f);
  EXPECT_FLOAT_EQ(s.parameters.sunAzimuth, 250.0f);
  EXPECT_FLOAT_EQ(s.parameters.turbidity, 3.0f);
  EXPECT_EQ(s.width, 256);
  EXPECT_EQ(s.height, 128);
  const SkySpec t = parseSkySpec(
      "sky:date=2003-10-17,time=12:30:30,utc=-7,latitude=39.742476,longitude=-105.1786,"
      "altitude=1830");
  EXPECT_NEAR(t.parameters.sunElevation, 90.0 - 50.11162, 0.02);
  for (const char* bad :
       {"sky:elevation=95", "sky:elevation=x", "sky:colour=3", "sky:elevation=10,date=2020-01-01",
        "sky:date=2020-02-30,time=1:00", "sky:date=2020-01-01,time=12:00", "sky:turbidity=0.5",
        "sky:size=10x99999", "sky:elevation", "sky:latitude=3"}) {
    try {
      parseSkySpec(bad);
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}
