// --env-intensity and --env-illuminance (an environment in physical units) in bake, render,
// probe and convert, and the photometry `ibl info` prints, end to end.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ibl/env/cubemap.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/json_file.hpp"
#include "ibl/math/color.hpp"
#include "support/helpers.hpp"
#include "support/numbers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// What a small bake needs besides its input and output.
const std::string kFloatBake =
    " --size 32 --irradiance-size 32 --dfg-size 16 --dfg-samples 64 --no-preview --format rgba32f";

CubeMap readCube(const std::filesystem::path& path) {
  DecodedFile d = readImageFile(path);
  CubeMap c;
  for (auto& level : d.levels) {
    c.levels.emplace_back();
    for (int f = 0; f < kFaceCount; ++f) c.levels.back()[f] = std::move(level[f]);
  }
  return c;
}

// The illuminance an upward surface receives according to a bake: pi times the irradiance
// cube's value at +Y (it stores E / pi), plus its suns' lux on the plane.
double bakedIlluminance(const std::filesystem::path& dir) {
  const CubeMap irradiance = readCube(dir / "irradiance.ktx2");
  double e = kPi * luminance(sampleBilinear(irradiance, 0, glm::vec3(0.0f, 1.0f, 0.0f)));
  const nlohmann::json m = readJsonFile(dir / "manifest.json");
  if (m.contains("lights"))
    for (const auto& l : m["lights"]) {
      const glm::vec3 d =
          glm::normalize(glm::vec3(l["direction"][0].get<float>(), l["direction"][1].get<float>(),
                                   l["direction"][2].get<float>()));
      glm::vec3 color(1.0f);
      if (l.contains("color"))
        color = {l["color"][0].get<float>(), l["color"][1].get<float>(),
                 l["color"][2].get<float>()};
      e += l["intensity"].get<double>() * luminance(color) * std::max(0.0f, d.y);
    }
  return e;
}

double maxRatioError(const CubeMap& a, const CubeMap& b, double ratio) {
  double worst = 0.0;
  for (int level = 0; level < a.levelCount(); ++level)
    for (int f = 0; f < kFaceCount; ++f)
      for (std::size_t i = 0; i < a.levels[level][f].pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
          const double x = a.levels[level][f].pixels[i][c];
          const double y = b.levels[level][f].pixels[i][c];
          worst = std::max(worst, std::abs(x - ratio * y) / (ratio * std::abs(y) + 1e-6));
        }
  return worst;
}

// A panorama lit only below the horizon.
void writeDarkSky(const std::filesystem::path& path) {
  Image img(64, 32);
  for (int y = 16; y < 32; ++y)
    for (int x = 0; x < 64; ++x) img.at(x, y) = glm::vec3(1.0f);
  writeFileAtomic(path, encodeExr(img, ExrPixelType::Float));
}

}  // namespace

// --env-illuminance 1000: the baked irradiance at +Y times pi is 1000 lux, and the manifest
// records the target, the factor and the illuminance measured before.
TEST(EnvScaleCli, BakeReachesTheIlluminance) {
  TempDir dir;
  const CliRun r = runIbl("bake " + quote(hdriPath("park")) + " -o " + quote(dir / "out") +
                          kFloatBake + " --env-illuminance 1000");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("--env-illuminance"), std::string::npos) << r.output;
  EXPECT_NEAR(bakedIlluminance(dir / "out"), 1000.0, 10.0);
  const nlohmann::json m = readJsonFile(dir / "out" / "manifest.json");
  const nlohmann::json& s = m.at("environment_scale");
  EXPECT_EQ(s.at("option"), "--env-illuminance");
  EXPECT_EQ(s.at("target_lux").get<double>(), 1000.0);
  const double measured = s.at("measured_lux").get<double>();
  EXPECT_GT(measured, 0.0);
  EXPECT_NEAR(s.at("factor").get<double>() * measured, 1000.0, 1e-6);
}

// A sky's sun is part of the environment: scaled with it, and counted in the illuminance.
TEST(EnvScaleCli, SkyIlluminanceIncludesTheSun) {
  TempDir dir;
  const CliRun r = runIbl("bake sky:elevation=30,size=128x64 -o " + quote(dir / "out") +
                          kFloatBake + " --env-illuminance 20000");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json m = readJsonFile(dir / "out" / "manifest.json");
  ASSERT_EQ(m.at("lights").size(), 1u);
  EXPECT_NEAR(bakedIlluminance(dir / "out"), 20000.0, 200.0);
  // Most of it is the sun's: without it, the sky alone would be far below the target.
  const CubeMap irradiance = readCube(dir / "out" / "irradiance.ktx2");
  EXPECT_LT(kPi * luminance(sampleBilinear(irradiance, 0, glm::vec3(0.0f, 1.0f, 0.0f))), 10000.0);
}

// --env-intensity 2 doubles every radiance output (not the DFG table); --bake DIR scaled at
// render time gives the render of the scaled bake.
TEST(EnvScaleCli, IntensityDoublesTheBakeAndScalesALoadedBake) {
  TempDir dir;
  const std::string park = quote(hdriPath("park"));
  ASSERT_EQ(runIbl("bake " + park + " -o " + quote(dir / "one") + kFloatBake).status, 0);
  const CliRun r =
      runIbl("bake " + park + " -o " + quote(dir / "two") + kFloatBake + " --env-intensity 2");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* file : {"specular.ktx2", "irradiance.ktx2", "source.ktx2"})
    EXPECT_LT(maxRatioError(readCube(dir / "two" / file), readCube(dir / "one" / file), 2.0), 1e-5)
        << file;
  EXPECT_EQ(readFileBytes(dir / "one" / "dfg.ktx2"), readFileBytes(dir / "two" / "dfg.ktx2"));
  const nlohmann::json m = readJsonFile(dir / "two" / "manifest.json");
  EXPECT_EQ(m.at("environment_scale").at("option"), "--env-intensity");
  EXPECT_EQ(m.at("environment_scale").at("factor").get<double>(), 2.0);
  EXPECT_FALSE(readJsonFile(dir / "one" / "manifest.json").contains("environment_scale"));
  const nlohmann::json sh1 = readJsonFile(dir / "one" / "sh.json");
  const nlohmann::json sh2 = readJsonFile(dir / "two" / "sh.json");
  EXPECT_NEAR(sh2.at("coefficients").at(0).at(1).get<double>(),
              2.0 * sh1.at("coefficients").at(0).at(1).get<double>(), 1e-5);

  const std::string render = " --size 32x32 --spp 1 --quiet -o ";
  ASSERT_EQ(
      runIbl("render sphere --bake " + quote(dir / "two") + render + quote(dir / "a.exr")).status,
      0);
  const CliRun scaled = runIbl("render sphere --bake " + quote(dir / "one") + " --env-intensity 2" +
                               render + quote(dir / "b.exr"));
  ASSERT_EQ(scaled.status, 0) << scaled.output;
  const Image a = readImageFile(dir / "a.exr").levels[0][0];
  const Image b = readImageFile(dir / "b.exr").levels[0][0];
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    worst = std::max(worst, maxRelativeError(b.pixels[i], a.pixels[i]));
  EXPECT_LT(worst, 1e-3);
}

// `ibl convert` writes the scaled pixels.
TEST(EnvScaleCli, ConvertWritesScaledPixels) {
  TempDir dir;
  const std::string park = quote(hdriPath("park"));
  ASSERT_EQ(runIbl("convert " + park + " -o " + quote(dir / "a.exr") + " --exr-type float --quiet")
                .status,
            0);
  ASSERT_EQ(runIbl("convert " + park + " -o " + quote(dir / "b.exr") +
                   " --exr-type float --quiet --env-intensity 3")
                .status,
            0);
  const Image a = readImageFile(dir / "a.exr").levels[0][0];
  const Image b = readImageFile(dir / "b.exr").levels[0][0];
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      worst = std::max(
          worst, std::abs(b.pixels[i][c] - 3.0 * a.pixels[i][c]) / (3.0 * a.pixels[i][c] + 1e-6));
  EXPECT_LT(worst, 1e-6);
}

// `ibl probe` records the distant environment's scale in each probe's manifest.
TEST(EnvScaleCli, ProbeManifestRecordsTheScale) {
  TempDir dir;
  const CliRun r = runIbl("probe grid --at 0,0,0.2 --proxy box:-7,-2,-1,7,2,1 --size 8 --spp 1 " +
                          std::string("--env ") + quote(hdriPath("park")) +
                          " --env-illuminance 5000 --quiet -o " + quote(dir / "probe"));
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json m = readJsonFile(dir / "probe" / "manifest.json");
  EXPECT_EQ(m.at("environment_scale").at("target_lux").get<double>(), 5000.0);
}

// `ibl info`: pi L lux for a constant L, and the luminance range, as text and JSON.
TEST(EnvScaleCli, InfoPrintsIlluminanceAndLuminance) {
  TempDir dir;
  Image img(64, 32);
  for (glm::vec3& p : img.pixels) p = glm::vec3(100.0f);
  img.at(0, 31) = glm::vec3(400.0f);
  writeFileAtomic(dir / "c.exr", encodeExr(img, ExrPixelType::Float));
  const CliRun text = runIbl("info " + quote(dir / "c.exr"));
  ASSERT_EQ(text.status, 0) << text.output;
  EXPECT_NE(text.output.find("illuminance 314.159 lx on an upward (+Y) surface"), std::string::npos)
      << text.output;
  EXPECT_NE(text.output.find("luminance   min 100, median 100,"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("max 400 nits"), std::string::npos) << text.output;
  const CliRun info = runIbl("info --json " + quote(dir / "c.exr"));
  ASSERT_EQ(info.status, 0) << info.output;
  const nlohmann::json j = nlohmann::json::parse(info.output);
  EXPECT_NEAR(j.at("horizontal_illuminance").get<double>(), 100.0 * kPi, 1e-3);
  EXPECT_NEAR(j.at("luminance").at("max").get<double>(), 400.0, 1e-3);
  EXPECT_NEAR(j.at("luminance").at("median").get<double>(), 100.0, 1e-3);
}

// Contradictory options, absurd values and an environment dark above the horizon: one line
// naming the option, a non-zero status, nothing written.
TEST(EnvScaleCli, BadUsesFailWithOneLineAndWriteNothing) {
  TempDir dir;
  writeDarkSky(dir / "dark.exr");
  const std::string park = quote(hdriPath("park"));
  const std::string out = quote(dir / "out");
  struct Case {
    std::string args;
    int status;
    std::string message;
  };
  const Case cases[] = {
      {"bake " + park + " -o " + out + " --env-intensity 2 --env-illuminance 1000", 2,
       "--env-illuminance: contradicts --env-intensity 2"},
      {"bake " + park + " -o " + out + " --env-intensity 0", 2,
       "--env-intensity: must be positive, not 0"},
      {"bake " + park + " -o " + out + " --env-intensity -2", 2,
       "--env-intensity: must be positive, not -2"},
      {"bake " + park + " -o " + out + " --env-intensity nan", 2, "--env-intensity: 'nan'"},
      {"bake " + park + " -o " + out + " --env-illuminance inf", 2, "--env-illuminance: 'inf'"},
      {"bake " + park + " -o " + out + " --env-intensity 1e38", 1, "exceed the range of a float"},
      {"bake " + quote(dir / "dark.exr") + " -o " + out + " --env-illuminance 1000", 1,
       "dark.exr: --env-illuminance: its horizontal illuminance is 0 lux"},
      {"render sphere --env none --env-intensity 2 -o " + quote(dir / "out.png"), 2,
       "--env-intensity: contradicts --env none"},
      {"render sphere --env " + quote(dir / "dark.exr") + " --env-illuminance 10 -o " +
           quote(dir / "out.png"),
       1, "--env-illuminance"},
      {"convert " + park + " -o " + quote(dir / "out.hdr") +
           " --env-intensity 2 --env-illuminance 5",
       2, "--env-illuminance: contradicts --env-intensity"},
      {"convert " + quote(dir / "dark.exr") + " -o " + quote(dir / "out.hdr") +
           " --env-illuminance 5",
       1, "--env-illuminance"},
      {"probe grid --at 0,0,0.2 -o " + out + " --env-intensity 1 --env-illuminance 5", 2,
       "--env-illuminance: contradicts --env-intensity"},
      {"view sphere --screenshot " + quote(dir / "out.png") + " --env-intensity 0", 2,
       "--env-intensity: must be positive"},
  };
  for (const Case& c : cases) {
    const CliRun r = runIbl("--quiet " + c.args);
    EXPECT_EQ(r.status, c.status) << c.args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("ibl: error: ", 0), 0u) << c.args << "\n" << r.output;
    // One line; a usage error that CLI11 finds adds the usual hint (--help) below it.
    const std::size_t end = r.output.find('\n');
    const std::string rest = r.output.substr(end + 1);
    EXPECT_TRUE(rest.empty() || rest.rfind("Run 'ibl --help'", 0) == 0) << c.args << "\n"
                                                                        << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << c.args;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.png")) << c.args;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.hdr")) << c.args;
  }
}
