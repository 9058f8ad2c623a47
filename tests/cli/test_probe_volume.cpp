// End-to-end tests of `ibl probe --volume` (apps/probe_volume.cpp) and `ibl render --volume`:
// the files an irradiance volume writes, its shards merged bit for bit, the relocation's record,
// the usage errors, and a render that reads it. Small volumes of the bundled room (5 x 3 x 5 m,
// a box and a sphere on the floor, lit by its own spot and point lights), 8 x 8 maps at 4 paths.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/ktx2.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;
namespace {

namespace fs = std::filesystem;

std::string volumeRoom() {
  return quote(dataDir() / "scenes" / "room.gltf");
}

// A volume of 2 x 2 x 2 probes inside the room, lit by its own lights (--env none: no bake),
// at `spp` paths per texel.
std::string roomVolume(int spp = 4) {
  return " --env none --volume 2,2,2 --bounds -2,0.5,-2,2,2.5,2 --volume-size 8 --bounces 1 "
         "--spp " +
         std::to_string(spp);
}

nlohmann::json volumeManifest(const fs::path& file) {
  return nlohmann::json::parse(readFileBytes(file)).at("irradiance_volume");
}

Image volumeAtlas(const fs::path& file) {
  Ktx2Texture t = decodeKtx2(readFileBytes(file), file.string());
  EXPECT_EQ(t.faceCount, 1);
  EXPECT_EQ(t.format, PixelFormat::Rgba32f);
  return std::move(t.levels.at(0).at(0));
}

}  // namespace

// One run of the whole volume, shared by the tests that read it.
class VolumeCli : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    const CliRun r = runIbl("probe " + volumeRoom() + roomVolume() + " -o " + quote(volume()));
    output_ = new std::string(r.output);
    ASSERT_EQ(r.status, 0) << r.output;
  }
  static void TearDownTestSuite() {
    delete dir_;
    delete output_;
  }
  static fs::path volume() { return dir_->path() / "volume"; }
  static TempDir* dir_;
  static std::string* output_;
};

TempDir* VolumeCli::dir_ = nullptr;
std::string* VolumeCli::output_ = nullptr;

// The three files, the atlases' sizes (tiles of texels + 2, nx * ny columns and nz rows), the
// manifest's grid and capture record, and a time per probe and in all.
TEST_F(VolumeCli, WritesTheAtlasesAndTheManifest) {
  EXPECT_NE(output_->find("[8/8] probe probe_1_1_1 at (1, 2, 1): capture "), std::string::npos)
      << *output_;
  EXPECT_NE(output_->find("8 probes in "), std::string::npos) << *output_;
  const Image irradiance = volumeAtlas(volume() / "irradiance.ktx2");
  EXPECT_EQ(irradiance.width, 2 * 2 * (8 + 2));
  EXPECT_EQ(irradiance.height, 2 * (8 + 2));
  const Image distance = volumeAtlas(volume() / "distance.ktx2");
  EXPECT_EQ(distance.width, 2 * 2 * (16 + 2));
  EXPECT_EQ(distance.height, 2 * (16 + 2));
  const nlohmann::json v = volumeManifest(volume() / "volume.json");
  EXPECT_EQ(v.at("counts"), nlohmann::json({2, 2, 2}));
  EXPECT_EQ(v.at("bounds"), nlohmann::json({{-2.0, 0.5, -2.0}, {2.0, 2.5, 2.0}}));
  EXPECT_EQ(v.at("origin"), nlohmann::json({-1.0, 1.0, -1.0}));
  EXPECT_EQ(v.at("spacing"), nlohmann::json({2.0, 1.0, 2.0}));
  EXPECT_EQ(v.at("irradiance").at("file"), "irradiance.ktx2");
  EXPECT_EQ(v.at("irradiance").at("texels"), 8);
  EXPECT_EQ(v.at("distance").at("file"), "distance.ktx2");
  EXPECT_EQ(v.at("distance").at("texels"), 16);
  EXPECT_EQ(v.at("capture_size"), 8);
  const nlohmann::json& capture = v.at("capture");
  EXPECT_EQ(capture.at("size"), 8);
  EXPECT_EQ(capture.at("spp"), 4);
  EXPECT_EQ(capture.at("bounces"), 1);
  EXPECT_EQ(capture.at("diffuse"), "disney");
  EXPECT_EQ(capture.at("multiscatter"), "walk");
  ASSERT_EQ(v.at("probes").size(), 8u);
  for (const auto& p : v.at("probes")) {
    EXPECT_TRUE(p.at("on").get<bool>()) << p.dump();
    EXPECT_TRUE(p.at("captured").get<bool>()) << p.dump();
  }
  // Every probe sees lit walls: the irradiance is not black. The distances are positive, at
  // most the capture's "far" (twice the cell's diagonal, 6 m), and their mean square is at least
  // their mean squared (Jensen).
  double sum = 0.0;
  for (const glm::vec3& e : irradiance.pixels) sum += e.x + e.y + e.z;
  EXPECT_GT(sum, 0.0);
  for (const glm::vec3& d : distance.pixels) {
    EXPECT_GT(d.x, 0.0f);
    EXPECT_LE(d.x, 6.0f);
    EXPECT_GE(d.y, d.x * d.x * (1.0f - 1e-4f));
  }
}

// Two shards and their merge give the unsharded run's atlases bit for bit (each probe is
// seeded by its index); a merge while a shard is missing names its probes and the shard, and
// writes nothing; a shard of another volume is refused.
TEST_F(VolumeCli, ShardsMergeIntoTheSameAtlases) {
  const fs::path shards = dir_->path() / "shards";
  CliRun r = runIbl("probe " + volumeRoom() + roomVolume() + " --shard 0/2 -o " + quote(shards));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(shards / "volume.shard-0-of-2.json"));
  EXPECT_TRUE(fs::exists(shards / "irradiance.volume.shard-0-of-2.ktx2"));
  EXPECT_TRUE(fs::exists(shards / "distance.volume.shard-0-of-2.ktx2"));
  r = runIbl("probe --merge " + quote(shards));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("the shards hold 4 of the grid's 8 probes; missing: probe_1_0_0, "
                          "probe_1_1_0, probe_1_0_1, probe_1_1_1 (owed by shard 1/2, which wrote "
                          "no volume.shard-1-of-2.json)"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(shards / "volume.json"));
  r = runIbl("probe " + volumeRoom() + roomVolume() + " --shard 1/2 -o " + quote(shards));
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("probe --merge " + quote(shards));
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* file : {"irradiance.ktx2", "distance.ktx2"})
    EXPECT_EQ(readFileBytes(shards / file), readFileBytes(volume() / file)) << file;
  nlohmann::json merged = volumeManifest(shards / "volume.json"),
                 whole = volumeManifest(volume() / "volume.json");
  merged["capture"].erase("milliseconds");
  whole["capture"].erase("milliseconds");
  EXPECT_EQ(merged, whole);
  // A shard of another volume (more paths) in the same folder.
  r = runIbl("probe " + volumeRoom() + roomVolume(8) + " --shard 1/3 -o " + quote(shards));
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("probe --merge " + quote(shards));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("volume.shard-1-of-3.json: belongs to another volume"), std::string::npos)
      << r.output;
}

// `ibl render --volume` reads it into the split sum: the image changes; a render of another
// shading refuses it (--force warns), and the reference refuses the option.
TEST_F(VolumeCli, RendersReadIt) {
  const std::string render = "render " + volumeRoom() + " --env none --size 32x24 -o ";
  const fs::path with = dir_->path() / "with.exr", without = dir_->path() / "without.exr";
  CliRun r = runIbl(render + quote(with) + " --volume " + quote(volume()));
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl(render + quote(without));
  ASSERT_EQ(r.status, 0) << r.output;
  const Image a = readImageFile(with).levels[0][0], b = readImageFile(without).levels[0][0];
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  double difference = 0.0, total = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const glm::vec3 d = glm::abs(a.pixels[i] - b.pixels[i]);
    difference += d.x + d.y + d.z;
    total += b.pixels[i].x + b.pixels[i].y + b.pixels[i].z;
  }
  EXPECT_GT(difference, 0.01 * total);
  // The live update run before the render (--volume-update-frames) changes the frame and says so.
  r = runIbl(render + quote(dir_->path() / "updated.exr") + " --volume " + quote(volume()) +
             " --volume-update-frames 3");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("volume updated over 3 frames"), std::string::npos) << r.output;
  EXPECT_NE(readImageFile(dir_->path() / "updated.exr").levels[0][0].pixels, a.pixels);
  r = runIbl(render + quote(dir_->path() / "lambert.exr") + " --diffuse lambert --volume " +
             quote(volume()));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("volume.json: captured with another shading (diffuse: disney in the "
                          "capture, lambert here)"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir_->path() / "lambert.exr"));
  r = runIbl(render + quote(dir_->path() / "lambert.exr") + " --diffuse lambert --force --volume " +
             quote(volume()));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("ibl: warning: "), std::string::npos) << r.output;
  // A folder that holds no volume.
  r = runIbl(render + quote(dir_->path() / "none.exr") + " --volume " + quote(dir_->path()));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("is not an irradiance volume (no volume.json)"), std::string::npos)
      << r.output;
}

// The volume's files are not replaced without --force.
TEST_F(VolumeCli, KeepsAnEarlierVolumeWithoutForce) {
  const auto before = readFileBytes(volume() / "irradiance.ktx2");
  CliRun r = runIbl("probe " + volumeRoom() + roomVolume() + " --seed 2 -o " + quote(volume()));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("volume.json: exists; pass --force"), std::string::npos) << r.output;
  EXPECT_EQ(readFileBytes(volume() / "irradiance.ktx2"), before);
}

// Probes inside geometry are moved out, or switched off with a warning and the reason in the
// manifest. The room's box fills [1.1, 1.7] x [0, 0.6] x [0.7, 1.3]: of two probes 0.4 apart at
// y = 0.3, z = 1, the one at x = 1.4 is 0.3 inside it, beyond the relocation's reach (0.45 of
// the spacing, 0.18), and the one at x = 1.8 is 0.1 in front of it, more than a fifth of the
// spacing: it stays. A probe 0.1 above the floor of a volume with 1 m cells is moved up.
TEST(VolumeCliRelocation, MovesProbesOutOrSwitchesThemOff) {
  const TempDir dir;
  const std::string options = " --env none --volume-size 8 --spp 4 --bounces 1";
  CliRun r = runIbl("probe " + volumeRoom() + options +
                    " --volume 2,1,1 --bounds 1.2,0.1,0.8,2.0,0.5,1.2 -o " + quote(dir / "off"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("ibl: warning: probe probe_0_0_0 at (1.4, 0.3, 1) switched off: inside "
                          "geometry"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("1 probes in "), std::string::npos) << r.output;
  nlohmann::json probes = volumeManifest(dir / "off" / "volume.json").at("probes");
  EXPECT_FALSE(probes[0].at("on").get<bool>());
  EXPECT_FALSE(probes[0].at("captured").get<bool>());
  EXPECT_NE(probes[0].value("reason", "").find("inside geometry"), std::string::npos);
  EXPECT_TRUE(probes[1].at("on").get<bool>());
  EXPECT_EQ(probes[1].at("offset"), nlohmann::json({0.0, 0.0, 0.0}));
  r = runIbl("probe " + volumeRoom() + options +
             " --volume 1,1,1 --bounds -0.5,-0.8,-0.5,0.5,1,0.5 -o " + quote(dir / "moved"));
  ASSERT_EQ(r.status, 0) << r.output;
  probes = volumeManifest(dir / "moved" / "volume.json").at("probes");
  EXPECT_TRUE(probes[0].at("on").get<bool>());
  EXPECT_GT(probes[0].at("offset")[1].get<double>(), 0.05);  // up, away from the floor
}

// Options that contradict --volume, or need it, are one-line usage errors naming both, found
// before anything is written.
TEST(VolumeCliUsage, ContradictionsAreUsageErrors) {
  const TempDir dir;
  const std::string probe = "probe " + volumeRoom() + " -o " + quote(dir / "v") + " ";
  const std::string volume = probe + "--volume 2,2,2 --bounds -1,1,-1,1,2,1 ";
  const std::pair<std::string, std::string> cases[] = {
      {volume + "--at 0,1,0", "--at: contradicts --volume"},
      {volume + "--grid 1,1,1", "--grid: contradicts --volume"},
      {volume + "--proxy none", "--proxy: shapes a local probe; a volume's probes (--volume)"},
      {volume + "--influence box:0,0,0,1,1,1", "--influence: shapes a local probe"},
      {volume + "--fade 0.1", "--fade: shapes a local probe"},
      {volume + "--rotation 0,1,0", "--rotation: shapes a local probe"},
      {volume + "--size 16",
       "--size: is the cube face size of local probes; a volume's map is "
       "--volume-size"},
      {probe + "--volume 2,2,2", "--volume: needs --bounds"},
      {probe + "--volume 0,2,2 --bounds -1,1,-1,1,2,1",
       "--volume: '0,2,2': each count must be a whole number from 1 to 64"},
      {probe + "--volume 65,1,1 --bounds -1,1,-1,1,2,1", "--volume: '65,1,1': each count"},
      {probe + "--volume 2,2,2 --bounds -9,1,-1,1,2,1", "--bounds: the probe at (-6.5, 1.25, "},
      {probe + "--at 0,1,0 --volume-size 8",
       "--volume-size: sets the irradiance volume, which "
       "needs --volume"},
      {probe + "--at 0,1,0 --volume-texels 4", "--volume-texels: sets the irradiance volume"},
      {probe + "--at 0,1,0 --normal-bias 0.1", "--normal-bias: sets the irradiance volume"},
      {probe + "--at 0,1,0 --view-bias 0.1", "--view-bias: sets the irradiance volume"},
      {"probe --merge " + quote(dir.path()) + " --volume 2,2,2", "--merge: merges the lists"},
      {"render " + volumeRoom() + " --mode reference --volume " + quote(dir.path()) + " -o " +
           quote(dir / "r.png"),
       "--volume: is the split sum's; --mode reference does not read it"},
  };
  for (const auto& [args, message] : cases) {
    const CliRun r = runIbl(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("ibl: error: ", 0), 0u) << args << "\n" << r.output;
    EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << args << ": one line\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos)
        << args << ": expected '" << message << "' in\n"
        << r.output;
  }
  EXPECT_TRUE(fs::is_empty(dir.path()));
}
