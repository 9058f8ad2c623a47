#include <numbers>
#include <set>
#include <tuple>

#include <tbb/global_control.h>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "ibl/bake/bake.hpp"
#include "ibl/bake/dfg.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

BakeOptions smallBake() {
  BakeOptions o;
  o.specular.size = 32;
  o.irradianceSize = 8;
  o.dfgSize = 16;
  o.dfgSamples = 64;
  return o;
}

Environment sunsetEnvironment() {
  return loadEnvironment(hdriPath("sunset").string()).environment;
}

}  // namespace

TEST(Bake, ConstantEnvironmentEverywhere) {
  const glm::vec3 L(0.7f, 1.3f, 2.0f);
  const BakeResult r = bakeEnvironment(equirectEnvironment(Image(128, 64, L)), smallBake());
  for (const auto& level : r.specular.levels)
    for (const auto& face : level)
      for (const auto& p : face.pixels) ASSERT_NEAR(glm::distance(p, L), 0.0f, 1e-5f);
  for (const auto& face : r.irradiance.levels[0])
    for (const auto& p : face.pixels) ASSERT_NEAR(glm::distance(p, L), 0.0f, 1e-5f);
  const glm::vec3 e = irradianceSh9(r.sh, glm::normalize(glm::vec3(0.3f, 0.9f, -0.1f)));
  EXPECT_NEAR(e.y, std::numbers::pi_v<float> * L.y, 1e-4f);
}

TEST(Bake, SameResultForAnyThreadCount) {
  const Environment env = sunsetEnvironment();
  BakeOptions o = smallBake();
  o.fresnelWeighted = true;
  BakeResult one, many;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = bakeEnvironment(env, o);
  }
  many = bakeEnvironment(env, o);
  ASSERT_EQ(one.specular.levelCount(), many.specular.levelCount());
  for (int m = 0; m < one.specular.levelCount(); ++m)
    for (int f = 0; f < 6; ++f) {
      EXPECT_EQ(one.specular.levels[m][f].pixels, many.specular.levels[m][f].pixels) << m;
      EXPECT_EQ(one.specularF0Zero->levels[m][f].pixels, many.specularF0Zero->levels[m][f].pixels)
          << m;
    }
  for (int f = 0; f < 6; ++f)
    EXPECT_EQ(one.irradiance.levels[0][f].pixels, many.irradiance.levels[0][f].pixels);
  EXPECT_EQ(one.dfg.pixels, many.dfg.pixels);
  for (int k = 0; k < 9; ++k) EXPECT_EQ(one.sh[k], many.sh[k]);
}

TEST(Bake, WritesEveryOutputAndAManifest) {
  TempDir dir;
  const BakeOptions o = smallBake();
  const BakeResult r = bakeEnvironment(sunsetEnvironment(), o);
  BakeOutputOptions out;
  out.exr = true;
  out.layout = Layout::Faces;
  const auto files = writeBakeOutputs(
      r, o, out, {"sunset.exr", "exr", "equirect", 512, 256, {}, 0.0f, {}}, dir / "assets");
  for (const auto& f : files) EXPECT_TRUE(std::filesystem::exists(f)) << f;
  const auto manifestBytes = readFileBytes(dir / "assets" / "manifest.json");
  const auto m = nlohmann::json::parse(manifestBytes.begin(), manifestBytes.end());
  EXPECT_EQ(m["conventions"]["cubemap"]["face_order"][0], "+X");
  EXPECT_EQ(m["conventions"]["roughness"]["alpha"], "r^2");
  std::set<std::string> roles;
  for (const auto& o2 : m["outputs"]) {
    roles.insert(o2["role"].get<std::string>());
    EXPECT_TRUE(std::filesystem::exists(dir / "assets" / o2["path"].get<std::string>()))
        << o2["path"];
    EXPECT_TRUE(o2.contains("format"));
    EXPECT_TRUE(o2.contains("size"));
  }
  EXPECT_EQ(roles,
            (std::set<std::string>{"specular", "irradiance", "sh", "dfg", "preview", "source"}));
  const auto& spec = m["outputs"][0];
  EXPECT_EQ(spec["role"], "specular");
  EXPECT_EQ(spec["levels"], 3);  // 32, 16, 8
  EXPECT_EQ(spec["roughness"].size(), 3u);
  EXPECT_FLOAT_EQ(spec["roughness"][1].get<float>(), 0.5f);
  // The KTX2 holds what the manifest says.
  const DecodedFile ktx = readImageFile(dir / "assets" / "specular.ktx2");
  EXPECT_EQ(ktx.levels.size(), 3u);
  EXPECT_EQ(ktx.levels[0].size(), 6u);
  for (const auto& sh : m["outputs"]) {
    if (sh["role"] == "sh") {
      EXPECT_NEAR(sh["coefficients"][0][0].get<float>(), r.sh[0].x, 1e-6f);
    }
  }
  // No staging directory left behind.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 1);
}

// The DFG and sheen tables are integrated once per process and kept: a later bake in the same
// process that asks for another size, sample count or sheen visibility gets its own table, the
// one integrateDfgLut / integrateSheenDfgLut give.
TEST(Bake, TablesKeptPerProcessAreThoseOfEachBakesSettings) {
  const Environment env =
      equirectEnvironment(equirectFromFunction(32, [](glm::vec3) { return glm::vec3(1.0f); }));
  BakeOptions o;
  o.specular.size = 8;
  o.irradianceSize = 4;
  o.sheen = true;
  for (const auto& [size, samples, visibility] :
       {std::tuple{16, 32, SheenVisibility::Charlie}, std::tuple{8, 32, SheenVisibility::Charlie},
        std::tuple{8, 64, SheenVisibility::Charlie}, std::tuple{8, 64, SheenVisibility::Neubelt},
        std::tuple{16, 32, SheenVisibility::Charlie}}) {
    o.dfgSize = size;
    o.dfgSamples = samples;
    o.sheenVisibility = visibility;
    const BakeResult r = bakeEnvironment(env, o);
    EXPECT_EQ(r.dfg.pixels, integrateDfgLut(size, size, samples).pixels) << size << " " << samples;
    ASSERT_TRUE(r.sheenDfg);
    EXPECT_EQ(r.sheenDfg->pixels, integrateSheenDfgLut(size, size, 4 * samples, visibility).pixels)
        << size << " " << samples;
  }
}
