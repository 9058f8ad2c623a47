// Every option of every command, given a value it cannot take: status 2 ("ibl: error: " and the
// option's name on the first line) for a wrong command line, 1 for a file that is missing or not
// what it says (a failure of the work), and nothing written either way. The table must name
// every option that `--help` lists: a new option cannot escape it.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// One wrong use of an option: the arguments after the command's base arguments, the status and
// a piece of the message.
struct Misuse {
  std::string option;  // as --help names it
  std::string args;
  int status;
  std::string message;
};

// The long options `ibl COMMAND --help` lists (each "--name" that starts an option's line, and
// a "!--no-name" negation).
std::set<std::string> longOptionsInHelp(const std::string& command) {
  const CliRun help = runIbl(command + " --help");
  std::set<std::string> options;
  const std::regex line(R"(^\s+(?:-\w,)?(--[\w-]+)(?:,!(--[\w-]+))?)");
  std::size_t begin = 0;
  while (begin < help.output.size()) {
    const std::size_t end = std::min(help.output.find('\n', begin), help.output.size());
    const std::string text = help.output.substr(begin, end - begin);
    std::smatch m;
    if (std::regex_search(text, m, line)) {
      options.insert(m[1].str());
      if (m[2].matched) options.insert(m[2].str());
    }
    begin = end + 1;
  }
  options.erase("--help");
  return options;
}

// Runs each misuse in a fresh folder; checks the status, the one-line error and that the
// folder holds nothing but what `prepare` put there.
void expectMisuses(const std::string& command, const std::string& base,
                   const std::vector<Misuse>& misuses) {
  std::set<std::string> covered;
  for (const Misuse& m : misuses) {
    covered.insert(m.option);
    TempDir dir;
    std::filesystem::copy_file(hdriPath("park"), dir / "park.exr");
    const std::string cd = "cd " + quote(dir.path()) + " && ";
    const CliRun r = runCommand(cd + IBL_CLI + " " + command + " " + base + " " + m.args);
    EXPECT_EQ(r.status, m.status) << command << " " << m.args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("ibl: error: ", 0), 0u) << command << " " << m.args << "\n"
                                                     << r.output;
    EXPECT_NE(r.output.find(m.message), std::string::npos)
        << command << " " << m.args << ": expected '" << m.message << "' in\n"
        << r.output;
    std::vector<std::string> left;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir.path()))
      if (e.path().filename() != "park.exr") left.push_back(e.path().filename().string());
    EXPECT_TRUE(left.empty()) << command << " " << m.args << " wrote " << left.front();
  }
  for (const std::string& option : longOptionsInHelp(command))
    EXPECT_TRUE(covered.count(option)) << command << " " << option << " has no misuse in the table";
}

// The options `ibl render` and `ibl view` share (apps/scene_options.cpp).
std::vector<Misuse> sceneMisuses() {
  return {
      {"--env", "--env nosuch.exr", 1, "nosuch.exr: no such file"},
      {"--env", "--env sky:elevation=100", 2, "elevation"},
      {"--strict", "--strict", 2, "--strict: applies to a glTF scene, not the built-in"},
      {"--variant", "--variant day", 2, "--variant: applies to a glTF scene, not the built-in"},
      {"--sheen-visibility", "--sheen-visibility ward", 2, "--sheen-visibility"},
      {"--lights", "--lights nosuch.json", 1, "nosuch.json: no such file"},
      {"--spot-lumens", "--spot-lumens lots", 2, "--spot-lumens"},
      {"--bake", "--bake nosuch", 1, "nosuch: no such directory"},
      {"--bake", "--bake . --env park.exr", 2, "--env: contradicts --bake"},
      {"--env-intensity", "--env-intensity 0", 2, "--env-intensity: must be positive, not 0"},
      {"--env-intensity", "--env none --env-intensity 2", 2,
       "--env-intensity: contradicts --env none"},
      {"--env-illuminance", "--env-illuminance 1000 --env-intensity 2", 2,
       "--env-illuminance: contradicts --env-intensity 2"},
      {"--env-illuminance", "--env-illuminance nan", 2, "--env-illuminance: 'nan'"},
      {"--camera", "--camera fisheye", 2, "--camera"},
      {"--fov", "--fov 500", 2, "--fov: must be from 1 to 179, not 500"},
      {"--ortho-width", "--ortho-width -1", 2, "--ortho-width: must be positive, not -1"},
      {"--look-from", "--look-from 1,2", 2, "--look-from: expected 3 comma-separated numbers"},
      {"--look-from", "--look-from 0,0,0 --look-at 0,0,0", 2, "--look-from: equals --look-at"},
      {"--look-at", "--look-at a,b,c", 2, "--look-at: 'a' is not a number"},
      {"--up", "--up 0,0,0", 2, "--up: must not be the zero vector"},
      {"--size", "--size 0x0", 2, "--size: expected WxH"},
      {"--base-color", "--base-color nan,1,1", 2, "--base-color: 'nan,1,1' is not finite"},
      {"--metallic", "--metallic 2", 2, "--metallic: must be from 0 to 1, not 2"},
      {"--roughness", "--roughness -1", 2, "--roughness: must be from 0 to 1, not -1"},
      {"--ior", "--ior 0.5", 2, "--ior: must be from 1 to 5, not 0.5"},
      {"--specular", "--specular 2", 2, "--specular: must be from 0 to 1, not 2"},
      {"--clearcoat", "--clearcoat 1.5", 2, "--clearcoat: must be from 0 to 1, not 1.5"},
      {"--clearcoat-roughness", "--clearcoat-roughness -0.5", 2,
       "--clearcoat-roughness: must be from 0 to 1, not -0.5"},
      {"--iridescence", "--iridescence 2", 2, "--iridescence: must be from 0 to 1, not 2"},
      {"--iridescence-ior", "--iridescence-ior 0.5", 2,
       "--iridescence-ior: must be from 1 to 3, not 0.5"},
      {"--iridescence-thickness", "--iridescence-thickness -5", 2,
       "--iridescence-thickness: must be from 0 to 2000, not -5"},
      {"--anisotropy", "--anisotropy 1.2", 2, "--anisotropy: must be from 0 to 1, not 1.2"},
      {"--anisotropy-rotation", "--anisotropy-rotation 400", 2,
       "--anisotropy-rotation: must be from -360 to 360, not 400"},
      {"--transmission", "--transmission -0.5", 2, "--transmission: must be from 0 to 1, not -0.5"},
      {"--thickness", "--transmission 1 --thickness 5000", 2,
       "--thickness: must be from 0 to 1000, not 5000"},
      {"--thickness", "--thickness 1", 2, "--thickness: makes a transmissive sphere solid"},
      {"--attenuation-distance", "--transmission 1 --thickness 1 --attenuation-distance 0", 2,
       "--attenuation-distance: must be positive, not 0"},
      {"--attenuation-distance", "--transmission 1 --attenuation-distance 2", 2,
       "--attenuation-distance: sets the absorption inside a volume; add --thickness"},
      {"--attenuation-color", "--transmission 1 --thickness 1 --attenuation-color 1,2,1", 2,
       "--attenuation-color: each channel must be from 0 to 1, not '1,2,1'"},
      {"--attenuation-color", "--transmission 1 --attenuation-color 0.5,0.5,0.5", 2,
       "--attenuation-color: sets the absorption inside a volume"},
      {"--diffuse", "--diffuse oren-nayar", 2, "--diffuse"},
      {"--only", "--only glossy", 2, "--only"},
      {"--multiscatter", "--multiscatter=maybe", 2, "--multiscatter"},
      {"--multiscatter", "--multiscatter maybe", 2, "--multiscatter"},
      {"--no-multiscatter", "--no-multiscatter=maybe", 2, "--no-multiscatter"},
      {"--no-multiscatter", "--no-multiscatter --multiscatter walk", 2, "--no-multiscatter"},
      {"--probes", "--probes nosuch", 1, "nosuch: no such directory"},
      {"--specular-aa", "--specular-aa maybe", 2, "--specular-aa"},
      {"--force", "--force=maybe", 2, "--force"},
      {"--no-parallax", "--no-parallax=maybe", 2, "--no-parallax"},
      {"--no-distance-roughness", "--no-distance-roughness=maybe", 2, "--no-distance-roughness"},
      {"--ao", "--ao -1", 2, "--ao: must be from 0 to 4096, not -1"},
      {"--ssao", "--ssao maybe", 2, "--ssao"},
      {"--ssao", "--ssao on --ao 4", 2, "--ssao: on contradicts --ao 4"},
      {"--ssao-radius", "--ssao-radius 0", 2, "--ssao-radius: must be positive, not 0"},
      {"--ssao-quality", "--ssao-quality ultra", 2, "--ssao-quality"},
      {"--ssr", "--ssr maybe", 2, "--ssr"},
      {"--ssr-quality", "--ssr-quality ultra", 2, "--ssr-quality"},
      {"--ssr-thickness", "--ssr-thickness 0", 2, "--ssr-thickness"},
      {"--specular-micro-occlusion", "--specular-micro-occlusion=maybe", 2,
       "--specular-micro-occlusion"},
      {"--shadows", "--shadows maybe", 2, "--shadows: 'maybe' is not none, map or ray"},
      {"--shadow-map-size", "--shadow-map-size 1000", 2, "--shadow-map-size"},
      {"--shadow-cascades", "--shadow-cascades 5", 2, "--shadow-cascades: must be from 1 to 4"},
      {"--no-dominant", "--no-dominant=maybe", 2, "--no-dominant"},
      {"--irradiance", "--irradiance sh9", 2, "--irradiance"},
      {"--area-lights", "--area-lights exact", 2, "--area-lights"},
      {"--background", "--background 1,2", 2, "--background: expected 3"},
      {"--ev100", "--ev100 nan", 2, "--ev100: 'nan' is not finite"},
      {"--aperture", "--aperture 0", 2, "--aperture: must be positive, not 0"},
      {"--shutter", "--shutter -1", 2, "--shutter: must be positive, not -1"},
      {"--iso", "--iso 0", 2, "--iso: must be positive, not 0"},
      {"--exposure-compensation", "--exposure-compensation inf", 2, "is not a finite number"},
      {"--tonemap", "--tonemap reinhard", 2, "--tonemap"},
      {"--bloom", "--bloom bright", 2, "--bloom: 'bright' is not a number"},
      {"--bloom", "--bloom 40", 2, "--bloom: 40 stops is beyond any exposure"},
  };
}

std::vector<Misuse> operator+(std::vector<Misuse> a, const std::vector<Misuse>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace

TEST(Usage, GlobalOptions) {
  const CliRun threads = runIbl("--threads 0 info park.exr");
  EXPECT_EQ(threads.status, 2);
  EXPECT_NE(threads.output.find("ibl: error: --threads: must be from 1 to 4096, not 0"),
            std::string::npos)
      << threads.output;
  const CliRun quiet = runIbl("--quiet=maybe info park.exr");
  EXPECT_EQ(quiet.status, 2) << quiet.output;
  const CliRun unknown = runIbl("bakee");
  EXPECT_EQ(unknown.status, 2) << unknown.output;
}

TEST(Usage, Bake) {
  expectMisuses(
      "bake", "--size 16",
      {
          {"--list", "--list nosuch.txt -o out", 1, "nosuch.txt: cannot read the list"},
          {"--shard", "park.exr --shard 0/2 -o out", 2, "--shard: splits a batch: it needs"},
          {"--shard", "park.exr sky:elevation=30 --shard 2/2 -o out", 2,
           "--shard: '2/2': expected K/N with 0 <= K < N"},
          {"--shard", "park.exr sky:elevation=30 --shard 1 -o out", 2, "--shard: '1'"},
          {"--shard", "park.exr sky:elevation=30 --shard 0/99999999999 -o out", 2,
           "--shard: '0/99999999999'"},
          {"--shard", "park.exr sky:elevation=30 --shard 0/2x -o out", 2, "--shard: '0/2x'"},
          {"--output", "", 2, "--output: an output directory is required"},
          {"--sheen-visibility", "-o out --sheen-visibility neubelt", 2,
           "--sheen-visibility: chooses the visibility of the sheen table, which only --sheen"},
          {"--sheen-visibility", "-o out --sheen --sheen-visibility ward", 2, "--sheen-visibility"},
          {"--output", "-o park.exr/x", 1, "park.exr"},
          {"--device", "--device tpu -o out", 2, "--device"},
          {"--list-devices", "--list-devices=maybe", 2, "--list-devices"},
          {"--input-layout", "park.exr --input-layout diagonal -o out", 2, "--input-layout"},
          {"--layer", "park.exr --layer NoSuchLayer -o out", 1, "NoSuchLayer"},
          {"--size", "--size 300 -o out", 2,
           "--size: must be a power of two from 1 to 4096, not 300"},
          {"--levels", "--levels 0 -o out", 2, "--levels: must be from 1 to 13, not 0"},
          {"--levels", "--levels 9 -o out", 2, "--levels: 9 levels need a cube of at least 256^2"},
          {"--mapping", "--mapping cubic -o out", 2, "--mapping"},
          {"--mapping", "--mapping frostbite --target gltf-sample-viewer -o out", 2,
           "--mapping linear"},
          {"--method", "--method magic -o out", 2, "--method"},
          {"--samples", "--samples 0 -o out", 2, "--samples: must be from 1 to 65536, not 0"},
          {"--fresnel-weighted", "--fresnel-weighted=maybe -o out", 2, "--fresnel-weighted"},
          {"--fresnel-weighted", "--fresnel-weighted --target babylon -o out", 2,
           "--fresnel-weighted: no target takes it"},
          {"--sheen", "--sheen=maybe -o out", 2, "--sheen"},
          {"--target", "--target unreal -o out", 2, "--target"},
          {"--irradiance-size", "--irradiance-size 1000 -o out", 2,
           "--irradiance-size: must be a power of two from 1 to 1024, not 1000"},
          {"--dfg-size", "--dfg-size 1 -o out", 2, "--dfg-size: must be from 2 to 4096, not 1"},
          {"--dfg-samples", "--dfg-samples 0 -o out", 2, "--dfg-samples: must be from 1 to"},
          {"--sh-window", "--sh-window=maybe -o out", 2, "--sh-window"},
          {"--rotate", "--rotate nan -o out", 2, "'nan' is not a finite number"},
          {"--clamp", "--clamp -5 -o out", 2, "--clamp: must be positive, not -5"},
          {"--format", "--format rgb565 -o out", 2, "--format"},
          {"--format", "--format rgba32f --target filament -o out", 2,
           "--format: no target takes it: --target filament writes its fixed R11F_G11F_B10F"},
          {"--exr", "--exr=maybe -o out", 2, "--exr"},
          {"--hdr", "--hdr --target dds -o out", 2, "--hdr: no target takes it"},
          {"--layout", "--layout diagonal -o out", 2, "--layout"},
          {"--force", "--force=maybe -o out", 2, "--force"},
          {"--no-preview", "--no-preview=maybe -o out", 2, "--no-preview"},
          {"--extract-sun", "sky:elevation=30 --extract-sun -o out", 2,
           "--extract-sun: contradicts sky:elevation=30"},
          {"--env-intensity", "--env-intensity -1 -o out", 2,
           "--env-intensity: must be positive, not -1"},
          {"--env-illuminance", "--env-illuminance 1000 --env-intensity 2 -o out", 2,
           "--env-illuminance: contradicts --env-intensity 2"},
          {"--env-illuminance", "--env-illuminance 0 -o out", 2,
           "--env-illuminance: must be positive, not 0"},
          {"--preview-size", "--preview-size 4 -o out", 2,
           "--preview-size: must be from 8 to 1024, not 4"},
          {"inputs", "nosuch.exr -o out", 1, "nosuch.exr: no such file"},
      });
}

TEST(Usage, Convert) {
  expectMisuses(
      "convert", "park.exr",
      {
          {"--list", "--list nosuch.txt -o '{name}.hdr'", 1, "nosuch.txt"},
          {"--output", "-o out.txt", 2, "out.txt: unknown output format"},
          {"--output", "-o park.exr", 2, "park.exr: is the input park.exr"},
          {"--layout", "-o out.hdr --layout diagonal", 2, "--layout"},
          {"--layout", "-o out.hdr --layout cube", 2, "--layout cube needs a .ktx2"},
          {"--input-layout", "-o out.hdr --input-layout diagonal", 2, "--input-layout"},
          {"--layer", "-o out.hdr --layer NoSuchLayer", 1, "NoSuchLayer"},
          {"--size", "-o out.hdr --size 0", 2, "--size: must be from 1 to 16384, not 0"},
          {"--size", "-o out.hdr --size 33 --layout equirect", 2, "must be even"},
          {"--format", "-o out.ktx2 --format rgb565", 2, "--format"},
          {"--format", "-o out.hdr --format rgba32f", 2, "--format applies to KTX2"},
          {"--exr-type", "-o out.exr --exr-type double", 2, "--exr-type"},
          {"--exposure", "-o out.png --exposure inf", 2, "is not a finite number"},
          {"--exposure", "-o out.exr --exposure 1", 2, "--exposure applies to PNG"},
          {"--rotate", "-o out.hdr --rotate nan", 2, "is not a finite number"},
          {"--mips", "-o out.hdr --mips --layout equirect", 2,
           "--mips applies to cube map outputs only"},
          {"--mips", "-o out.ktx2 --mips --size 100", 2,
           "--mips needs a power-of-two size, not 100"},
          {"--extract-sun", "-o out.hdr --extract-sun", 2, "--extract-sun: needs"},
          {"--sun-json", "-o out.hdr --sun-json sun.json", 2, "--sun-json: applies"},
          {"--repair-damage", "sky:elevation=30 -o out.hdr --repair-damage", 2,
           "--repair-damage: contradicts sky:elevation=30"},
          {"--env-intensity", "-o out.hdr --env-intensity inf", 2, "--env-intensity: 'inf'"},
          {"--env-illuminance", "-o out.hdr --env-illuminance 5 --env-intensity 2", 2,
           "--env-illuminance: contradicts --env-intensity 2"},
      });
}

// The scene options' misuses with the arguments a command needs appended.
static std::vector<Misuse> sceneMisusesWith(const std::string& args) {
  std::vector<Misuse> misuses = sceneMisuses();
  for (Misuse& m : misuses) m.args += " " + args;
  return misuses;
}

TEST(Usage, Render) {
  expectMisuses("render", "sphere --spp 1",
                sceneMisusesWith("-o out.png") +
                    std::vector<Misuse>{
                        {"--output", "-o out.jpg", 2, "out.jpg: output must be .exr or .png"},
                        {"--output", "-o park.exr --env park.exr", 2, "is the input park.exr"},
                        {"--mode", "-o out.png --mode fast", 2, "--mode"},
                        {"--spp", "-o out.png --spp 0", 2, "--spp: must be from 1 to"},
                        {"--noise", "-o out.png --noise 2", 2, "--noise: must be from 0 to 1"},
                        {"--bounces", "-o out.png --bounces -1", 2, "--bounces: must be from 0"},
                        {"--shadows", "-o out.png --mode reference --shadows map", 2,
                         "--shadows: map is the split sum's"},
                        {"--shadow-rays", "-o out.png --shadows ray --shadow-rays 0", 2,
                         "--shadow-rays: must be from 1"},
                        {"--exr-exposed", "-o out.exr --exr-exposed=maybe", 2, "--exr-exposed"},
                        {"--seed", "-o out.png --seed -1", 2, "--seed"},
                        {"--device", "-o out.png --mode reference --device tpu", 2, "--device"},
                        {"--volume", "-o out.png --volume nosuch", 1, "nosuch: no such directory"},
                        {"--volume-update-frames", "-o out.png --volume-update-frames 3", 2,
                         "--volume-update-frames: updates the volume of --volume"},
                        {"--volume-update-frames", "-o out.png --volume-update-frames -1", 2,
                         "--volume-update-frames: must be from 0 to"},
                        {"--device", "-o out.png --device gpu", 2,
                         "--device: gpu runs the reference: add --mode reference"},
                        {"--noise", "-o out.png --mode reference --device gpu --noise 0.1", 2,
                         "--noise: adaptive stopping is the CPU reference's"},
                    });
}

TEST(Usage, View) {
  // Every misuse is found before the Vulkan device is opened: no GPU needed.
  expectMisuses(
      "view", "sphere",
      sceneMisusesWith("--screenshot out.png") +
          std::vector<Misuse>{
              {"--screenshot", "--screenshot out.jpg", 2, "output must be .exr"},
              {"--spp", "--screenshot out.png --spp 3", 2, "--spp"},
              {"--skybox-mip", "--screenshot out.png --skybox-mip -1", 2,
               "--skybox-mip: must be from 0 to 16, not -1"},
              {"--frames", "--frames -1", 2, "--frames: must be from 0"},
              {"--reference", "--screenshot out.png --reference full", 2, "--reference"},
              {"--reference-spp", "--screenshot out.png --reference-spp 4", 2,
               "--reference-spp: needs --reference"},
              {"--reference-spp", "--screenshot out.png --reference reference --reference-spp 0", 2,
               "--reference-spp: must be from 1 to 1048576, not 0"},
              {"--reference-spp", "--screenshot out.png --reference split --reference-spp 2000000",
               2, "--reference-spp: must be from 1 to 1048576, not 2000000"},
              {"--ao", "--screenshot out.png --ao 4", 2,
               "ray-cast ambient occlusion is `ibl render`'s alone"},
              {"--shadows", "--screenshot out.png --shadows ray", 2,
               "--shadows: ray is `ibl render`'s alone"},
              {"--volume", "--screenshot out.png --volume nosuch", 1, "nosuch: no such directory"},
              {"--volume-update", "--screenshot out.png --volume-update on", 2,
               "--volume-update: updates the volume of --volume"},
              {"--volume-update", "--screenshot out.png --volume-update sometimes", 2,
               "--volume-update"},
              {"--volume-update-frames", "--screenshot out.png --volume-update-frames 2", 2,
               "--volume-update-frames: updates the volume of --volume"},
              {"--volume-update-frames",
               "--screenshot out.png --volume . --volume-update off --volume-update-frames 2", 2,
               "--volume-update-frames: contradicts --volume-update off"},
              {"--volume-update-frames", "--frames 1 --volume . --volume-update-frames 2", 2,
               "--volume-update-frames: runs before a --screenshot"},
              {"--auto-exposure", "--screenshot out.png --auto-exposure on --ev100 5", 2,
               "--auto-exposure: on contradicts a fixed exposure"},
              {"--auto-exposure", "--screenshot out.png --auto-exposure sometimes", 2,
               "--auto-exposure"},
              {"--metering", "--screenshot out.png --metering 90,10", 2,
               "--metering: 90,10: wants two percentiles LOW,HIGH with 0 <= LOW < HIGH <= 100"},
              {"--metering", "--screenshot out.png --metering 5", 2, "--metering"},
              {"--adaptation-speed", "--frames 1 --adaptation-speed -1", 2,
               "--adaptation-speed: must be from 0 to 1000, not -1"},
              {"--panel", "--frames 1 --panel sometimes", 2, "--panel"},
              {"--buffer", "--screenshot out.png --buffer depth", 2, "--buffer"},
              {"--clay", "--screenshot out.png --clay maybe", 2, "--clay"},
              {"--split", "--screenshot out.png --split 0.3", 2,
               "--split: places the boundary of the split view; the screenshot needs --reference "
               "split"},
              {"--split", "--screenshot out.png --reference split --split 1.5", 2,
               "--split: must be from 0 to 1, not 1.5"},
              {"--taa", "--screenshot out.png --taa 0", 2,
               "--taa: 0: wants on, off, or the frames a screenshot averages, 1 to 4096"},
              {"--taa", "--screenshot out.png --taa 8x", 2, "--taa: 8x: wants on, off"},
              {"--taa", "--screenshot out.png --taa 8 --buffer normals", 2,
               "--taa: averages jittered frames of the shading; --buffer normals shows"},
              {"--clay", "--screenshot out.png --clay on --reference difference", 2,
               "--clay: draws the real-time frame as clay; --reference difference shows"},
              {"--buffer", "--screenshot out.png --buffer roughness --reference split", 2,
               "--buffer: roughness is a buffer of the real-time frame; --reference split shows "
               "the shading"},
              {"--settings", "--screenshot out.png --settings nosuch.json", 1,
               "nosuch.json: no such file"},
          });
}

// A settings file (--settings) with a mistake: one line naming the file and the setting, before
// anything is loaded.
TEST(Usage, ViewSettingsFileMistakesNameTheFile) {
  const TempDir dir;
  const auto run = [&](const std::string& text) {
    const auto path = dir / "settings.json";
    std::ofstream(path) << text;
    return runIbl("view sphere --screenshot " + (dir / "out.png").string() + " --settings " +
                  path.string());
  };
  const std::string name = (dir / "settings.json").string();
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {R"({"zoom": 2})", name + ": unknown setting \"zoom\""},
           {R"({"fov": "wide"})", name + ": \"fov\" must be a number"},
           {R"({"tonemap": "reinhard"})",
            name + ": \"tonemap\" must be one of aces, filmic, none, not \"reinhard\""},
           {R"({"look_from": [1, 2]})", name + ": \"look_from\" must be [x, y, z]"},
           {R"({"auto_exposure": 1})", name + ": \"auto_exposure\" must be true or false"},
           {R"({"buffer": "depth"})", name + ": \"buffer\" must be a buffer's name"},
           {R"({"buffer": "normals", "view": "split"})",
            name + ": \"buffer\" shows the real-time frame, not the \"split\" view"},
           {R"({"clay": "yes"})", name + ": \"clay\" must be true or false"},
           {R"({"taa": 16})", name + ": \"taa\" must be true or false"},
           {R"({"split": 2})", name + ": \"split\" must be from 0 to 1, not 2"},
           {R"([1, 2])", name + ": is not a JSON object of settings"},
           {R"({"fov": 40,})", name + ": line 1, column 12"}}) {
    const CliRun r = run(text);
    EXPECT_EQ(r.status, 1) << text << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << text << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.png")) << text;
  }
}

TEST(Usage, Probe) {
  expectMisuses(
      "probe", "--size 8 --spp 1",
      {
          {"--env", "grid --at 0,0,0 -o out --env nosuch.exr", 1, "nosuch.exr: no such file"},
          {"--strict", "grid --at 0,0,0 -o out --strict", 2, "--strict: applies to a glTF"},
          {"--variant", "grid --at 0,0,0 -o out --variant day", 2, "--variant: applies to a glTF"},
          {"--sheen-visibility", "grid --at 0,0,0 -o out --sheen-visibility ward", 2,
           "--sheen-visibility"},
          {"--lights", "grid --at 0,0,0 -o out --lights nosuch.json", 1,
           "nosuch.json: no such file"},
          {"--bake", "grid --at 0,0,0 -o out --bake nosuch", 1, "nosuch: no such directory"},
          {"--env-intensity", "grid --at 0,0,0 -o out --env-intensity 0", 2,
           "--env-intensity: must be positive, not 0"},
          {"--env-illuminance", "grid --at 0,0,0 -o out --env-illuminance 5 --env-intensity 2", 2,
           "--env-illuminance: contradicts --env-intensity 2"},
          {"--output", "grid --at 0,0,0", 2, "--output: an output directory is required"},
          {"--at", "grid --at 1,2 -o out", 2, "--at: expected 3 comma-separated numbers"},
          {"--at", "grid -o out", 2, "give either --at X,Y,Z"},
          {"--grid", "grid --grid 0,1,1 --bounds -1,-1,-1,1,1,1 -o out", 2,
           "--grid: '0,1,1': each count must be a whole number from 1 to 64"},
          {"--bounds", "grid --grid 1,1,1 --bounds 1,1,1,0,0,0 -o out", 2,
           "--bounds: '1,1,1,0,0,0'"},
          {"--shard", "grid --grid 1,1,1 --bounds -1,-1,-1,1,1,1 --shard 3/2 -o out", 2, "--shard"},
          {"--merge", "--merge nosuch", 1, "nosuch: holds no probes.shard-K-of-N.json"},
          {"--merge", "--merge . grid --at 0,0,0", 2, "--merge: merges the lists"},
          {"--proxy", "grid --at 0,0,0 -o out --proxy cone:1", 2, "--proxy: 'cone:1': expected"},
          {"--influence", "grid --at 0,0,0 -o out --influence box:1", 2, "--influence"},
          {"--rotation", "grid --at 0,0,0 -o out --rotation a,b,c", 2, "--rotation: 'a'"},
          {"--fade", "grid --at 0,0,0 -o out --fade -1", 2, "--fade: must be 0 or more, not -1"},
          {"--size", "grid --at 0,0,0 -o out --size 12", 2,
           "--size: must be a power of two from 8 to 1024, not 12"},
          {"--spp", "grid --at 0,0,0 -o out --spp 0", 2, "--spp: must be from 1 to"},
          {"--bounces", "grid --at 0,0,0 -o out --bounces -1", 2, "--bounces: must be from 0"},
          {"--capture-specular", "grid --at 0,0,0 -o out --capture-specular=maybe", 2,
           "--capture-specular"},
          {"--seed", "grid --at 0,0,0 -o out --seed x", 2, "--seed"},
          {"--multiscatter", "grid --at 0,0,0 -o out --multiscatter maybe", 2, "--multiscatter"},
          {"--no-multiscatter", "grid --at 0,0,0 -o out --no-multiscatter --multiscatter scale", 2,
           "--no-multiscatter"},
          {"--force", "grid --at 0,0,0 -o out --force=maybe", 2, "--force"},
          {"--diffuse", "grid --at 0,0,0 -o out --diffuse oren-nayar", 2, "--diffuse"},
          {"--specular-micro-occlusion", "grid --at 0,0,0 -o out --specular-micro-occlusion=maybe",
           2, "--specular-micro-occlusion"},
          {"--volume", "grid --at 0,0,0 --volume 2,2,2 -o out", 2, "--at: contradicts --volume"},
          {"--volume-size", "grid --at 0,0,0 -o out --volume-size 3", 2,
           "--volume-size: must be from 4 to 256, not 3"},
          {"--volume-texels", "grid --at 0,0,0 -o out --volume-texels 64", 2,
           "--volume-texels: must be from 2 to 32, not 64"},
          {"--normal-bias", "grid --at 0,0,0 -o out --normal-bias -1", 2,
           "--normal-bias: must be from 0 to 1, not -1"},
          {"--view-bias", "grid --at 0,0,0 -o out --view-bias 0.5", 2,
           "--view-bias: sets the irradiance volume, which needs --volume"},
          {"--exclude", "grid --at 0,0,0 -o out --exclude chair", 2,
           "--exclude: no node or mesh of the scene is named 'chair'"},
      });
}

TEST(Usage, Sky) {
  expectMisuses(
      "sky", "--size 16x8",
      {
          {"--output", "-o out.txt", 2, "out.txt: unknown output format"},
          {"--sun-elevation", "-o out.exr --sun-elevation 100", 2,
           "--sun-elevation: must be from -90 to 90, not 100"},
          {"--sun-azimuth", "-o out.exr --sun-azimuth 400", 2, "--sun-azimuth"},
          {"--date",
           "-o out.exr --date 2020-13-01 --time 12:00 --latitude 0 "
           "--longitude 0",
           2, "--date"},
          {"--time",
           "-o out.exr --date 2020-06-01 --time 25:00 --latitude 0 "
           "--longitude 0",
           2, "--time"},
          {"--utc-offset", "-o out.exr --utc-offset 20", 2, "--utc-offset"},
          {"--latitude", "-o out.exr --latitude 100", 2, "--latitude"},
          {"--longitude", "-o out.exr --longitude 200", 2, "--longitude"},
          {"--altitude", "-o out.exr --altitude -1", 2, "--altitude"},
          {"--turbidity", "-o out.exr --turbidity 0", 2, "--turbidity"},
          {"--ozone", "-o out.exr --ozone -1", 2, "--ozone"},
          {"--ground-albedo", "-o out.exr --ground-albedo 2", 2, "--ground-albedo"},
          {"--size", "-o out.exr --size 3x3", 2, "--size"},
          {"--sun-json", "-o out.exr --sun-json out.exr", 2, "--sun-json: is the image"},
          {"--sun-disk", "-o out.exr --sun-disk=maybe", 2, "--sun-disk"},
          {"--device", "-o out.exr --device tpu", 2, "--device"},
          {"--single-scattering", "-o out.exr --single-scattering=maybe", 2, "--single-scattering"},
      });
}

TEST(Usage, CompareAndInfo) {
  expectMisuses("compare", "park.exr park.exr",
                {
                    {"--mask", "--mask nosuch.png", 1, "nosuch.png: no such file"},
                    {"--error-png", "--error-png park.exr", 2, "park.exr: is the input"},
                    {"--error-scale", "--error-scale 0", 2, "--error-scale: must be positive"},
                    {"--max-rel-error", "--max-rel-error -1", 2, "--max-rel-error: must be 0"},
                    {"--json", "--json=maybe", 2, "--json"},
                });
  expectMisuses("info", "",
                {
                    {"--input-layout", "park.exr --input-layout diagonal", 2, "--input-layout"},
                    {"--layer", "park.exr --layer NoSuchLayer", 1, "NoSuchLayer"},
                    {"--json", "park.exr --json=maybe", 2, "--json"},
                    {"file", "nosuch.exr", 1, "nosuch.exr: no such file"},
                });
}

TEST(Usage, Completion) {
  expectMisuses("completion", "",
                {
                    {"shell", "fish", 2, "shell: 'fish' is not bash or zsh"},
                    {"shell", "", 2, "shell: required (bash or zsh)"},
                    {"shell", "bash zsh", 2, "zsh"},
                });
}

namespace {

// A usage error's whole output: status 2, one line, with every piece of `pieces`.
void expectOneLineUsageError(const std::string& args, const std::vector<std::string>& pieces) {
  const CliRun r = runIbl(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
  EXPECT_EQ(r.output.rfind("ibl: error: ", 0), 0u) << args << "\n" << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << "\n" << r.output;
  for (const std::string& piece : pieces)
    EXPECT_NE(r.output.find(piece), std::string::npos)
        << args << ": expected '" << piece << "' in\n"
        << r.output;
}

}  // namespace

// Options that another option makes meaningless (the command would ignore them) are usage errors
// naming both, found before any work: nothing is written.
TEST(Usage, OptionsThatOthersMakeMeaninglessNameBoth) {
  TempDir dir;
  const std::string png = " -o " + quote(dir / "out.png");
  const std::string exr = " -o " + quote(dir / "out.exr");
  const std::string shot = " --screenshot " + quote(dir / "out.png");
  const std::string bake = "bake --size 16 -o " + quote(dir / "b");
  const std::string probe = "probe grid --size 8 --spp 1 -o " + quote(dir / "p");
  const std::string gltf = quote(dataDir() / "models" / "bunny.glb");
  // The arguments, and the two options the message names (the first one leads it).
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      // The exposure: --ev100, or the three settings of a camera together.
      {"render sphere --ev100 5 --aperture 2.8 --shutter 0.01 --iso 100" + png,
       {"--ev100: contradicts --aperture 2.8"}},
      {"render sphere --aperture 2.8" + png, {"--aperture:", "--shutter and --iso"}},
      {"render sphere --aperture 2.8 --iso 100" + png, {"--aperture:", "--shutter"}},
      {"view sphere --shutter 0.01" + shot, {"--shutter:", "--aperture and --iso"}},
      // The mode: the split sum's options with the reference, the reference's without.
      {"render sphere --mode reference --ssao on" + png, {"--ssao: on", "--mode reference"}},
      {"render sphere --mode reference --ssr on" + png, {"--ssr: on", "--mode reference"}},
      {"render sphere --mode split-sum --bounces 3" + png, {"--bounces:", "--mode reference"}},
      {"render sphere --bounces 0" + png, {"--bounces:", "--mode reference"}},
      {"render sphere --mode reference --shadows none" + png,
       {"--shadows: none contradicts --bounces 4"}},
      {"render sphere --noise 0.1" + png, {"--noise:", "--spp 4 (the default)"}},
      {"render sphere --mode reference --spp 8 --noise 0.1" + png, {"--noise:", "--spp 8"}},
      {"render " + gltf + " --mode reference --ao 4" + png, {"--ao:", "--mode reference"}},
      {"render sphere --mode reference --probes " + quote(dir.path()) + png,
       {"--probes:", "--mode reference"}},
      {"render sphere --mode reference --no-dominant" + png,
       {"--no-dominant:", "--mode reference"}},
      {"render sphere --mode reference --specular-aa off" + png,
       {"--specular-aa:", "--mode reference"}},
      {"render sphere --mode reference --irradiance sh" + png,
       {"--irradiance:", "--mode reference"}},
      {"render sphere --mode reference --area-lights frostbite" + png,
       {"--area-lights:", "--mode reference"}},
      {"render sphere --mode reference --shadows ray --shadow-map-size 512" + png,
       {"--shadow-map-size:", "--mode reference"}},
      {"render sphere --mode reference --shadow-cascades 2" + png,
       {"--shadow-cascades:", "--mode reference"}},
      {"render " + gltf + " --mode reference --ssao-quality high" + png,
       {"--ssao-quality:", "--mode reference"}},
      {"render " + gltf + " --mode reference --ssr-thickness 0.1" + png,
       {"--ssr-thickness:", "--mode reference"}},
      // The camera's kind (a glTF file's own camera: GltfCli.TheScenesCameraLeavesNoRoom).
      {"render sphere --camera ortho --fov 30" + png, {"--fov:", "--camera perspective"}},
      {"view sphere --ortho-width 2" + shot, {"--ortho-width:", "--camera ortho"}},
      {"render sphere --camera perspective --ortho-width 2" + png,
       {"--ortho-width:", "--camera ortho"}},
      // The built-in scenes' material.
      {"render " + gltf + " --metallic 1" + png, {"--metallic:", "built-in scenes"}},
      {"render " + gltf + " --base-color 1,0,0" + png, {"--base-color:", "built-in scenes"}},
      {"render grid --roughness 0.2" + png, {"--roughness:", "built-in sphere"}},
      {"render " + gltf + " --ior 1.33" + png, {"--ior:", "built-in scenes"}},
      {"render " + gltf + " --specular 0.5" + png, {"--specular:", "built-in scenes"}},
      {"render " + gltf + " --clearcoat 1" + png, {"--clearcoat:", "built-in scenes"}},
      {"render " + gltf + " --iridescence 1" + png, {"--iridescence:", "built-in scenes"}},
      {"render " + gltf + " --anisotropy 1" + png, {"--anisotropy:", "built-in scenes"}},
      {"render " + gltf + " --transmission 1" + png, {"--transmission:", "built-in scenes"}},
      // Settings of what is off.
      {"render sphere --ssao-quality high" + png, {"--ssao-quality:", "add --ssao on"}},
      {"render " + gltf + " --ssao off --ssao-radius 0.5" + png, {"--ssao-radius:", "--ssao off"}},
      {"render " + gltf + " --ao 4 --ssao-quality low" + png, {"--ssao-quality:", "--ao 4"}},
      {"view sphere --ssr-quality high" + shot, {"--ssr-quality:", "add --ssr on"}},
      {"render " + gltf + " --ssr off --ssr-thickness 0.1" + png,
       {"--ssr-thickness:", "--ssr off"}},
      {"render sphere --shadows none --shadow-map-size 512" + png,
       {"--shadow-map-size:", "--shadows none"}},
      {"view sphere --shadows none --shadow-cascades 2" + shot,
       {"--shadow-cascades:", "--shadows none"}},
      {"render sphere --shadow-rays 4" + png, {"--shadow-rays:", "--shadows ray"}},
      {"render sphere --no-parallax" + png, {"--no-parallax:", "--probes"}},
      {"view sphere --no-distance-roughness" + shot, {"--no-distance-roughness:", "--probes"}},
      {"render sphere --force" + png, {"--force:", "--probes"}},
      {"render sphere --spot-lumens frostbite" + png, {"--spot-lumens:", "--lights"}},
      // The window's options with a screenshot.
      {"view sphere --frames 10" + shot, {"--frames:", "--screenshot"}},
      {"view sphere --skybox-mip 2 --background 0,0,0" + shot,
       {"--skybox-mip:", "--background 0,0,0"}},
      {"view sphere --skybox-mip 2 --env none" + shot, {"--skybox-mip:", "--env none"}},
      // bake.
      {bake + " --no-preview --preview-size 64", {"--preview-size: contradicts --no-preview"}},
      {bake + " --layout faces", {"--layout:", "--exr or --hdr"}},
      {bake + " --samples 128", {"--samples:", "--method sampled"}},
      {bake + " sky:elevation=30 --layer Combined", {"--layer:", "sky:elevation=30"}},
      {bake + " sky:elevation=30 --input-layout cross", {"--input-layout:", "sky:elevation=30"}},
      // probe.
      {probe + " --at 0,0,0 --bounds -1,-1,-1,1,1,1", {"--bounds:", "--grid"}},
      {probe + " --at 0,0,0 --rotation 0,45,0", {"--rotation:", "--proxy or --influence"}},
  };
  for (const auto& [args, pieces] : cases) expectOneLineUsageError(args, pieces);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
  // What a linear image leaves out is harmless (the image is right): a note naming the options
  // and the image, and the image is written.
  const std::string render = "render sphere --env none --size 8x8 --spp 1 ";
  const std::pair<std::string, std::string> notes[] = {
      {render + "--tonemap filmic --ev100 3" + exr,
       "ibl: note: --tonemap, --ev100: no effect: " + (dir / "out.exr").string() +
           " holds linear radiance; add --exr-exposed or write a .png (and no --bloom reads"},
      {render + "--exposure-compensation 1 --bloom 2" + exr, ""},  // the bloom reads it
      {render + "--exr-exposed" + png,
       "ibl: note: --exr-exposed: no effect: " + (dir / "out.png").string() + " is exposed"},
  };
  for (const auto& [args, note] : notes) {
    const CliRun r = runIbl(args);
    EXPECT_EQ(r.status, 0) << args << "\n" << r.output;
    if (note.empty())
      EXPECT_EQ(r.output.find("ibl: note:"), std::string::npos) << args << "\n" << r.output;
    else
      EXPECT_NE(r.output.find(note), std::string::npos) << args << "\n" << r.output;
  }
}

// CLI11's parse errors in the project's words, one line each: what was expected, and the nearest
// command or option for a misspelling (by edit distance).
TEST(Usage, ParseErrorsSayWhatWasExpected) {
  const std::pair<std::string, std::vector<std::string>> cases[] = {
      {"frobnicate",
       {"ibl: error: unknown command 'frobnicate'; the commands are bake, convert, render"}},
      {"bakee", {"ibl: error: unknown command 'bakee'; did you mean bake?"}},
      {"--threads 2 rendr sphere", {"unknown command 'rendr'; did you mean render?"}},
      {"", {"ibl: error: a command is required: bake, convert"}},
      {"bake --sizee 64", {"ibl: error: unknown option --sizee; did you mean --size?"}},
      {"render sphere --roughnes 0.5 -o x.png",
       {"unknown option --roughnes; did you mean "
        "--roughness?"}},
      {"render sphere --zzz -o x.png", {"unknown option --zzz; `ibl render --help` lists"}},
      {"--threds 2 info x.exr", {"unknown option --threds; did you mean --threads?"}},
      {"bake --size 64x64", {"ibl: error: --size: '64x64' is not a power of two from 1 to 4096"}},
      {"render sphere --fov wide -o x.png", {"--fov: 'wide' is not a number from 1 to 179"}},
      {"render sphere --fov", {"--fov: expects a value: a number from 1 to 179"}},
      {"render --mode reference --shadows sphere", {"--shadows: 'sphere' is not none, map or ray"}},
      {"render sphere -o x.png --shadows", {"--shadows: expects a value: none, map or ray"}},
      {"render sphere --camera fisheye -o x.png",
       {"--camera: 'fisheye' is not perspective or ortho"}},
      {"render sphere", {"ibl: error: --output: required (output image"}},
      {"bake --exr=maybe", {"--exr: is a switch: give it without a value, not 'maybe'"}},
      {"info a.exr b.exr", {"unexpected argument 'b.exr'; `ibl info --help`"}},
      {"render sphere -o x.png --no-multiscatter --multiscatter walk",
       {"--multiscatter: contradicts --no-multiscatter"}},
  };
  for (const auto& [args, pieces] : cases) expectOneLineUsageError(args, pieces);
}
