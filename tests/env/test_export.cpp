// Exporting an environment (ibl/env/export.hpp), what `ibl convert` writes: the power the
// clamping to a format's range removes, worked by hand; the files each layout gives, named per
// level and face; and the options refused before any source is read.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/env/export.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

// A panorama of radiance 2 clamped to 1: every component clamped, half the power lost.
TEST(Export, ClampingReportsThePowerItRemoves) {
  Environment env = equirectEnvironment(Image(8, 4, glm::vec3(2.0f)));
  const RangeLoss loss = clampEnvironment(env, 1.0f);
  EXPECT_EQ(loss.clamped, 3u * 8u * 4u);
  EXPECT_EQ(loss.brightest, 2.0f);
  EXPECT_NEAR(loss.lostPower, 0.5, 1e-9);
  for (const glm::vec3& p : env.equirect.pixels) EXPECT_EQ(p, glm::vec3(1.0f));
  EXPECT_EQ(describe(loss, 1.0f),
            "96 values above 1 clamped (brightest 2), 50 % of the power lost");
  // Within the range: nothing.
  EXPECT_EQ(clampEnvironment(env, 4.0f).clamped, 0u);
}

TEST(Export, EachLayoutGivesItsFilesNamedPerLevelAndFace) {
  const Environment env =
      cubeEnvironment(cubeFromFunction(4, [](glm::vec3 d) { return d + glm::vec3(1.0f); }));
  ExportOptions o;
  o.output = "out/sky.hdr";  // a cube map: a horizontal cross by default
  std::vector<EncodedFile> files = encodeEnvironment(env, o);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].path, "out/sky.hdr");
  o.layout = Layout::Faces;
  o.output = "out/sky_{face}.hdr";
  o.mips = true;  // 4^2, 2^2, 1^2
  files = encodeEnvironment(env, o);
  ASSERT_EQ(files.size(), 18u);
  EXPECT_EQ(files[0].path, "out/sky_px_m0.hdr");
  EXPECT_EQ(files[17].path, "out/sky_nz_m2.hdr");
  // Every file written is among the paths checked before reading.
  const std::vector<std::filesystem::path> possible = possibleExportPaths(o);
  for (const EncodedFile& f : files)
    EXPECT_NE(std::find(possible.begin(), possible.end(), f.path), possible.end()) << f.path;
  o.output = "out/sky.ktx2";  // one file: the cube with its chain
  o.layout.reset();
  EXPECT_EQ(encodeEnvironment(env, o).size(), 1u);
}

TEST(Export, OptionsAreCheckedBeforeTheSource) {
  const auto refused = [](const ExportOptions& o) {
    try {
      checkExportOptions(o);
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  ExportOptions o;
  o.output = "a.gif";
  EXPECT_EQ(refused(o), "a.gif: unknown output format (use .ktx2, .exr, .hdr or .png)");
  o.output = "a.exr";
  o.layout = Layout::Cube;
  EXPECT_NE(refused(o).find("--layout cube needs a .ktx2 output"), std::string::npos);
  o.layout = Layout::Equirect;
  o.size = 33;
  EXPECT_NE(refused(o).find("must be even, not 33"), std::string::npos);
  o.layout = Layout::HCross;
  o.mips = true;
  o.size = 48;
  EXPECT_NE(refused(o).find("power-of-two size, not 48"), std::string::npos);
  o.size = 64;
  EXPECT_EQ(checkExportOptions(o), FileFormat::Exr);
}
