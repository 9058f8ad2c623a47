// `ibl sky`, sky: environments in bake / render / convert, and --extract-sun, end to end.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ibl/env/sky.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/json_file.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/light.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

double meanLuminance(const std::filesystem::path& exr) {
  const Image img = readImageFile(exr).levels.at(0).at(0);
  double s = 0.0;
  for (const glm::vec3& p : img.pixels) s += luminance(p);
  return s / static_cast<double>(img.pixels.size());
}

}  // namespace

TEST(SkyCli, WritesTheSkyAndItsSunAndRejectsBadOptions) {
  TempDir dir;
  const CliRun r = runIbl("sky -o " + quote(dir / "sky.exr") +
                          " --size 64x32 --sun-elevation 40 "
                          "--sun-azimuth 90 --sun-json " +
                          quote(dir / "sun.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const DecodedFile sky = readImageFile(dir / "sky.exr");
  EXPECT_EQ(sky.levels[0][0].width, 64);
  const std::vector<Light> lights = readLightsFile(dir / "sun.json");
  ASSERT_EQ(lights.size(), 1u);
  EXPECT_EQ(lights[0].type, LightType::Sun);
  EXPECT_GT(lights[0].intensity, 80000.0f);
  EXPECT_GT(glm::dot(lights[0].direction,
                     glm::vec3(std::cos(glm::radians(40.0f)), std::sin(glm::radians(40.0f)), 0.0f)),
            0.99999f);
  // Errors: one line naming the problem, nothing written.
  for (const std::string& bad :
       {"--sun-disk --sun-json " + quote(dir / "x.json"), std::string("--date 2026-06-21"),
        std::string("--date 2026-13-01 --time 12:00 --latitude 1 --longitude 2"),
        std::string("--sun-elevation 10 --date 2026-06-21 --time 12:00 --latitude 1 --longitude 2"),
        std::string("--size 64x"), std::string("--sun-elevation 100"),
        std::string("--turbidity 0.5")}) {
    const CliRun e = runIbl("sky -o " + quote(dir / "bad.exr") + " " + bad);
    EXPECT_NE(e.status, 0) << bad;
    EXPECT_NE(e.output.find("ibl: error"), std::string::npos) << bad << ": " << e.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.exr")) << bad;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.json")) << bad;
  }
}

TEST(SkyCli, BakeAndRenderASkyWithItsSun) {
  TempDir dir;
  const std::string sky = "sky:elevation=35,azimuth=200,size=128x64";
  ASSERT_EQ(runIbl("bake " + sky + " -o " + quote(dir / "bake") +
                   " --size 32 --dfg-size 16 --dfg-samples 64 --no-preview -q")
                .status,
            0);
  const nlohmann::json m = readJsonFile(dir / "bake" / "manifest.json");
  ASSERT_EQ(m.at("lights").size(), 1u);
  EXPECT_EQ(m["lights"][0]["type"], "sun");
  EXPECT_NEAR(m["sky"]["sun_elevation"].get<double>(), 35.0, 1e-6);
  EXPECT_EQ(m["source"]["path"], sky);  // the description as given, not a path
  // The same sky as a plain image (no sun) lights a sphere far less than the bake, whose
  // manifest brings the sun: the sun is in the render.
  // (The image baked as small as the sky's bake, to compare like with like.)
  ASSERT_EQ(runIbl("convert " + sky + " -o " + quote(dir / "sky.exr")).status, 0);
  ASSERT_EQ(runIbl("bake " + quote(dir / "sky.exr") + " -o " + quote(dir / "image") +
                   " --size 32 --dfg-size 16 --dfg-samples 64 --no-preview -q")
                .status,
            0);
  const std::string common = " sphere --size 24x24 --spp 1 --background 0,0,0 -q -o ";
  CliRun a = runIbl("render --bake " + quote(dir / "bake") + common + quote(dir / "a.exr"));
  ASSERT_EQ(a.status, 0) << a.output;
  CliRun b = runIbl("render --bake " + quote(dir / "image") + common + quote(dir / "b.exr"));
  ASSERT_EQ(b.status, 0) << b.output;
  CliRun c = runIbl("render --env " + sky + common + quote(dir / "c.exr"));
  ASSERT_EQ(c.status, 0) << c.output;
  const double withSun = meanLuminance(dir / "a.exr"), skyOnly = meanLuminance(dir / "b.exr");
  EXPECT_GT(withSun, 2.0 * skyOnly);
  EXPECT_NEAR(meanLuminance(dir / "c.exr"), withSun, 0.02 * withSun);
}

TEST(SkyCli, ExtractSunRecoversThePaintedSun) {
  // A sky with its sun painted in (ibl sky --sun-disk), baked with --extract-sun: the manifest's
  // sun is the sky's own (ibl sky --sun-json) in lux, direction and color.
  TempDir dir;
  // 2048 x 1024: the sun's disk (0.533 degrees) spans three pixels, so its size can be measured.
  const std::string angles = " --sun-elevation 25 --sun-azimuth 140 --size 2048x1024";
  ASSERT_EQ(runIbl("sky -o " + quote(dir / "painted.exr") + angles + " --sun-disk").status, 0);
  ASSERT_EQ(runIbl("sky -o " + quote(dir / "plain.exr") + angles + " --sun-json " +
                   quote(dir / "sun.json"))
                .status,
            0);
  const Light truth = readLightsFile(dir / "sun.json").at(0);
  const CliRun r =
      runIbl("bake " + quote(dir / "painted.exr") + " --extract-sun -o " + quote(dir / "bake") +
             " --size 32 --dfg-size 16 --dfg-samples 64 --no-preview");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("extracted the sun"), std::string::npos) << r.output;
  const nlohmann::json m = readJsonFile(dir / "bake" / "manifest.json");
  const std::vector<Light> found =
      parseLights(nlohmann::json({{"lights", m.at("lights")}}).dump(), "manifest", dir.path());
  ASSERT_EQ(found.size(), 1u);
  std::printf(
      "extracted %.0f lx (sky's sun %.0f lx), %.3f degrees off, %.3f degrees wide\n",
      found[0].intensity, truth.intensity,
      glm::degrees(std::acos(std::min(1.0f, glm::dot(found[0].direction, truth.direction)))),
      glm::degrees(found[0].angularDiameter));
  EXPECT_NEAR(found[0].intensity, truth.intensity, 0.02 * truth.intensity);
  EXPECT_GT(glm::dot(found[0].direction, truth.direction), std::cos(glm::radians(0.2f)));
  EXPECT_NEAR(found[0].color.z, truth.color.z, 0.03f);
  // The Sun's angular diameter, 2 asin(R / au) = 0.533 degrees (IAU 2015 nominal radius at 1 au),
  // in the sun file and as extracted from the painted disk (the diameter of a uniform disk with
  // the brightest pixel's radiance: measured 0.496 degrees, the limb-darkened disk's center
  // being brighter than its mean); a disk twice as wide reads about 1 degree.
  const double diameter = glm::degrees(2.0 * std::asin(6.957e8 / 1.495978707e11));
  EXPECT_NEAR(glm::degrees(truth.angularDiameter), diameter, 1e-3);
  EXPECT_NEAR(glm::degrees(found[0].angularDiameter), diameter, 0.1);
  // convert --extract-sun writes the image without its sun and the lights file, together.
  ASSERT_EQ(runIbl("convert " + quote(dir / "painted.exr") + " --extract-sun --sun-json " +
                   quote(dir / "x.json") + " -o " + quote(dir / "desunned.exr") + " -q")
                .status,
            0);
  EXPECT_EQ(readLightsFile(dir / "x.json").size(), 1u);
  EXPECT_NEAR(meanLuminance(dir / "desunned.exr"), meanLuminance(dir / "plain.exr"),
              0.01 * meanLuminance(dir / "plain.exr"));
  // No sun to find: an error naming the file; --extract-sun without --sun-json: an error.
  const CliRun none =
      runIbl("bake " + quote(dir / "plain.exr") + " --extract-sun -o " + quote(dir / "none"));
  EXPECT_NE(none.status, 0);
  EXPECT_NE(none.output.find("plain.exr: --extract-sun: no compact bright source"),
            std::string::npos)
      << none.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "none"));
  const CliRun noJson =
      runIbl("convert " + quote(dir / "painted.exr") + " --extract-sun -o " + quote(dir / "y.exr"));
  EXPECT_NE(noJson.status, 0);
  EXPECT_FALSE(std::filesystem::exists(dir / "y.exr"));
}
