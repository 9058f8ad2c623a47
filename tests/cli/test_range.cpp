// Values beyond a format's range and inputs without light: no output holds an infinity or a
// NaN, what clamping loses is reported and recorded, and a black input is an error.
#include <cmath>
#include <map>
#include <numbers>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"
#include "support/exr_writer.hpp"
#include "support/helpers.hpp"
#include "support/numbers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// A 64x32 panorama: a sky of radiance 1 and a 2x2-pixel sun of 2e6 (real captures reach 1e5
// and more), as a float EXR.
Image sunPanorama() {
  Image img(64, 32, glm::vec3(1.0f));
  for (int y = 10; y < 12; ++y)
    for (int x = 20; x < 22; ++x) img.at(x, y) = glm::vec3(2e6f, 1.8e6f, 1.5e6f);
  return img;
}

void writeExr(const std::filesystem::path& path, const Image& img) {
  writeExrWithOpenExr(img, path);  // can hold NaN, which ibl's own encoder never writes
}

// The fraction of a panorama's power (luminance x solid angle) above `limit`, computed here:
// pixel (x, y) of W x H spans (2 pi / W) x (cos(pi y / H) - cos(pi (y + 1) / H)) steradians.
double powerAbove(const Image& img, double limit) {
  double total = 0.0, above = 0.0;
  for (int y = 0; y < img.height; ++y) {
    const double omega = 2.0 * kPi / img.width *
                         (std::cos(kPi * y / img.height) - std::cos(kPi * (y + 1) / img.height));
    for (int x = 0; x < img.width; ++x) {
      const glm::dvec3 v(img.at(x, y));
      const glm::dvec3 excess = glm::max(v - limit, glm::dvec3(0.0));
      total += omega * (0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z);
      above += omega * (0.2126 * excess.x + 0.7152 * excess.y + 0.0722 * excess.z);
    }
  }
  return above / total;
}

// The same fraction for level 0 of a cube map, each texel's solid angle integrated here by a
// 4 x 4 midpoint rule over the face plane (dA / (1 + s^2 + t^2)^(3/2)).
double powerAbove(const DecodedFile& cube, double limit) {
  double total = 0.0, above = 0.0;
  const int n = cube.levels[0][0].width;
  for (const Image& face : cube.levels[0])
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        double omega = 0.0;
        for (int j = 0; j < 4; ++j)
          for (int i = 0; i < 4; ++i) {
            const double s = 2.0 * (x + (i + 0.5) / 4.0) / n - 1.0;
            const double t = 2.0 * (y + (j + 0.5) / 4.0) / n - 1.0;
            omega += (4.0 / (16.0 * n * n)) / std::pow(1.0 + s * s + t * t, 1.5);
          }
        const glm::dvec3 v(face.at(x, y));
        const glm::dvec3 excess = glm::max(v - limit, glm::dvec3(0.0));
        total += omega * (0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z);
        above += omega * (0.2126 * excess.x + 0.7152 * excess.y + 0.0722 * excess.z);
      }
  return above / total;
}

bool allFinite(const DecodedFile& d) {
  for (const auto& level : d.levels)
    for (const auto& face : level)
      for (const auto& p : face.pixels)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  return true;
}

nlohmann::json outputOf(const std::filesystem::path& manifest, const std::string& path) {
  const auto bytes = readFileBytes(manifest);
  const nlohmann::json parsed = nlohmann::json::parse(bytes.begin(), bytes.end());
  for (const auto& o : parsed["outputs"])
    if (o["path"] == path) return o;
  return {};
}

const std::string kSmallBake = " --size 16 --dfg-size 16 --dfg-samples 64 --no-preview";

}  // namespace

TEST(Range, SunsBeyondHalfFloatAreClampedAndReported) {
  TempDir dir;
  writeExr(dir / "sun.exr", sunPanorama());
  // rgba16f (default) and the packed formats: finite files, a warning, the loss in the manifest.
  std::map<std::string, double> lost;
  for (const char* format : {"rgba16f", "e5b9g9r9", "b10g11r11"}) {
    const auto out = dir / format;
    const CliRun r = runIbl("bake " + quote(dir / "sun.exr") + " -o " + quote(out) + kSmallBake +
                            " --exr --format " + format);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("source.ktx2: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(std::string("values above the ") + format + " range clamped"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("--format rgba32f"), std::string::npos) << r.output;
    for (const char* file : {"source.ktx2", "specular.ktx2", "irradiance.ktx2"})
      EXPECT_TRUE(allFinite(readImageFile(out / file))) << format << " " << file;
    EXPECT_TRUE(allFinite(readImageFile(out / "source_m0.exr")));  // half EXR copies too
    const auto source = outputOf(out / "manifest.json", "source.ktx2");
    ASSERT_TRUE(source.contains("clamped")) << source.dump();
    EXPECT_GT(source["clamped"]["values"].get<int>(), 0);
    EXPECT_GT(source["clamped"]["brightest"].get<double>(), 1e6);
    lost[format] = source["clamped"]["lost_power"].get<double>();
  }
  // rgba32f keeps everything: no warning, nothing clamped.
  const CliRun r = runIbl("bake " + quote(dir / "sun.exr") + " -o " + quote(dir / "f32") +
                          kSmallBake + " --format rgba32f");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("clamped"), std::string::npos) << r.output;
  EXPECT_FALSE(outputOf(dir / "f32" / "manifest.json", "source.ktx2").contains("clamped"));
  // The reported loss is what clamping the exact source cube loses (level 0, the finest, loses
  // the most), computed here from the float bake.
  const DecodedFile exact = readImageFile(dir / "f32" / "source.ktx2");
  EXPECT_NEAR(lost["rgba16f"], powerAbove(exact, 65504.0), 2e-3);
  EXPECT_NEAR(lost["e5b9g9r9"], powerAbove(exact, 65408.0), 2e-3);
  EXPECT_GT(lost["rgba16f"], 0.5);  // the sun is most of the power, most of it above the limit
}

TEST(Range, ClampOptionRemovesWhatItSays) {
  TempDir dir;
  const Image img = sunPanorama();
  writeExr(dir / "sun.exr", img);
  const CliRun r = runIbl("bake " + quote(dir / "sun.exr") + " -o " + quote(dir / "b") +
                          kSmallBake + " --clamp 1000");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("--clamp: 12 values above 1000 clamped"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("range clamped"), std::string::npos) << r.output;  // now representable
  const auto bytes = readFileBytes(dir / "b" / "manifest.json");
  const auto clamp = nlohmann::json::parse(bytes.begin(), bytes.end())["source"]["clamp"];
  EXPECT_EQ(clamp["limit"].get<double>(), 1000.0);
  EXPECT_EQ(clamp["values"].get<int>(), 12);
  EXPECT_NEAR(clamp["lost_power"].get<double>(), powerAbove(img, 1000.0), 1e-6);
  // The clamped source holds nothing far above the limit: the resampling's Catmull-Rom spline
  // overshoots the edge of the clamped plateau by a few percent (1.75 % here), no more.
  const DecodedFile source = readImageFile(dir / "b" / "source.ktx2");
  for (const auto& face : source.levels[0])
    for (const auto& p : face.pixels) ASSERT_LE(std::max({p.x, p.y, p.z}), 1030.0f);
}

TEST(Range, ConvertWarnsAndWritesNoInfinity) {
  TempDir dir;
  writeExr(dir / "sun.exr", sunPanorama());
  for (const char* out : {"s.ktx2", "s.exr"}) {
    const CliRun r =
        runIbl("convert " + quote(dir / "sun.exr") + " -o " + quote(dir / out) + " --size 64");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("ibl: warning: " + (dir / out).string() + ": "), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("values above 65504 clamped (brightest"), std::string::npos)
        << r.output;
    EXPECT_TRUE(allFinite(readImageFile(dir / out))) << out;
  }
  // A float EXR keeps the sun: no warning.
  const CliRun r = runIbl("convert " + quote(dir / "sun.exr") + " -o " + quote(dir / "f.exr") +
                          " --exr-type float");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
  EXPECT_EQ(readImageFile(dir / "f.exr").levels[0][0].at(20, 10).x, 2e6f);
}

TEST(Range, InputsWithoutLightAreRejected) {
  TempDir dir;
  writeExr(dir / "nan.exr", Image(16, 8, glm::vec3(std::nanf(""))));
  writeExr(dir / "black.exr", Image(16, 8, glm::vec3(0.0f)));
  writeExr(dir / "negative.exr", Image(16, 8, glm::vec3(-1.0f)));
  for (const char* name : {"nan.exr", "black.exr", "negative.exr"}) {
    CliRun r = runIbl("bake " + quote(dir / name) + " -o " + quote(dir / "out") + kSmallBake);
    EXPECT_EQ(r.status, 1) << name;
    EXPECT_NE(r.output.find((dir / name).string() + ": holds no light"), std::string::npos)
        << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
    r = runIbl("render sphere --size 8x8 --env " + quote(dir / name) + " -o " +
               quote(dir / "r.png"));
    EXPECT_EQ(r.status, 1) << name;
    EXPECT_NE(r.output.find("holds no light"), std::string::npos) << r.output;
    r = runIbl("info " + quote(dir / name));
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("brightest   none"), std::string::npos) << r.output;
    r = runIbl("info --json " + quote(dir / name));
    EXPECT_TRUE(nlohmann::json::parse(r.output)["brightest_direction"].is_null()) << r.output;
  }
}
