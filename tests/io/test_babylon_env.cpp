// Babylon.js's .env container: a round trip through the encoder and the decoder, and damaged
// files rejected with the file's name (the files as Babylon's loader reads them:
// tests/bake/test_targets.cpp).
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/io/babylon_env.hpp"
#include "support/containers.hpp"

using namespace ibl;
using namespace ibl::test;

TEST(Targets, BabylonEnvRoundTripsAndRejectsDamage) {
  BabylonEnvironment env;
  env.width = 4;
  for (int m = 0; m < 3; ++m) {
    env.levels.emplace_back();
    for (int f = 0; f < 6; ++f) {
      Image face(4 >> m, 4 >> m);
      for (std::size_t i = 0; i < face.pixels.size(); ++i)
        face.pixels[i] = glm::vec3(0.01f * (f + 1), 3.0f * m + i, 100.0f + f);
      env.levels.back().push_back(face);
    }
  }
  env.polynomial[4] = glm::vec3(1, 2, 3);
  const std::vector<std::uint8_t> bytes = encodeBabylonEnv(env);
  const BabylonEnvironment back = decodeBabylonEnv(bytes, "a.env");
  ASSERT_EQ(back.levels.size(), 3u);
  EXPECT_EQ(back.polynomial[4], glm::vec3(1, 2, 3));
  for (int m = 0; m < 3; ++m)
    for (int f = 0; f < 6; ++f)
      for (std::size_t i = 0; i < env.levels[m][f].pixels.size(); ++i)
        EXPECT_LT(rgbdError(back.levels[m][f].pixels[i], env.levels[m][f].pixels[i]), 0.02);
  // Damage: truncated payload, a broken manifest, a foreign image type, a wrong level count.
  const auto fails = [](std::vector<std::uint8_t> b, const std::string& what) {
    try {
      decodeBabylonEnv(b, "bad.env");
      ADD_FAILURE() << "accepted: " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("bad.env"), std::string::npos) << e.what();
    }
  };
  fails(std::vector<std::uint8_t>(bytes.begin(), bytes.end() - 10), "truncated");
  std::vector<std::uint8_t> brokenJson = bytes;
  brokenJson[9] = '#';
  fails(brokenJson, "broken JSON");
  const std::string text(bytes.begin() + 8, std::find(bytes.begin() + 8, bytes.end(), 0));
  const auto withText = [&](const std::string& t) {  // the manifest replaced by t
    const std::string all =
        std::string(bytes.begin(), bytes.begin() + 8) + t +
        std::string(bytes.begin() + 8 + static_cast<std::ptrdiff_t>(text.size()), bytes.end());
    return std::vector<std::uint8_t>(all.begin(), all.end());
  };
  std::string webp = text;
  webp.replace(webp.find("image/png"), 9, "image/wbp");
  fails(withText(webp), "webp");
  std::string wide = text;
  wide.replace(wide.find("\"width\":4"), 9, "\"width\":8");
  fails(withText(wide), "level count");
}
