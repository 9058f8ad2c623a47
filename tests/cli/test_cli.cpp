// End-to-end tests of the `ibl` executable: exit codes, outputs, and error messages.
#include <array>
#include <cstdio>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

int countFiles(const std::filesystem::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace

TEST(Cli, Version) {
  const CliRun r = runIbl("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("ibl 0."), std::string::npos);
}

TEST(Cli, ConvertToKtx2CubeWithMips) {
  TempDir dir;
  const CliRun r = runIbl("convert " + quote(hdriPath("sunset")) + " -o " + quote(dir / "s.ktx2") +
                          " --size 64 --mips --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, "");  // --quiet
  const DecodedFile d = readImageFile(dir / "s.ktx2");
  EXPECT_EQ(d.levels.size(), 7u);
  EXPECT_EQ(d.levels[0].size(), 6u);
  EXPECT_EQ(d.levels[0][0].width, 64);
}

TEST(Cli, ConvertToFacesAndMipFiles) {
  TempDir dir;
  CliRun r = runIbl("convert " + quote(hdriPath("park")) + " -o " + quote(dir / "f_{face}.png") +
                    " --layout faces --size 16 --exposure -1");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"px", "nx", "py", "ny", "pz", "nz"})
    EXPECT_TRUE(std::filesystem::exists(dir / (std::string("f_") + f + ".png"))) << f;
  r = runIbl("convert " + quote(hdriPath("park")) + " -o " + quote(dir / "c.exr") +
             " --layout vcross --size 8 --mips --exr-type float");
  ASSERT_EQ(r.status, 0) << r.output;
  for (int m = 0; m < 4; ++m) {
    const DecodedFile d = readImageFile(dir / ("c_m" + std::to_string(m) + ".exr"));
    EXPECT_EQ(d.levels[0][0].width, 3 * (8 >> m));
  }
  // Back from six faces to an equirect HDR, rotated.
  r = runIbl("convert " + quote(dir / "f_{face}.png") + " -o " + quote(dir / "e.hdr") +
             " --rotate 45");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(readImageFile(dir / "e.hdr").levels[0][0].width, 64);
}

TEST(Cli, InfoJson) {
  const CliRun r = runIbl("info --json " + quote(hdriPath("studio")));
  ASSERT_EQ(r.status, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["format"], "exr");
  EXPECT_EQ(j["layout"], "equirect");
  EXPECT_EQ(j["width"], 512);
  EXPECT_EQ(j["negative"], 2028);
  EXPECT_GT(j["radiant_integral"][0].get<double>(), 0.0);
}

TEST(Cli, InfoText) {
  const CliRun r = runIbl("info " + quote(hdriPath("sunset")));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("exr (half, DWAB)"), std::string::npos);
  EXPECT_NE(r.output.find("912 negative"), std::string::npos);
}

TEST(Cli, BadInputsFailCleanlyAndWriteNothing) {
  TempDir dir;
  std::filesystem::create_directories(dir / "out");
  std::ofstream(dir / "corrupt.exr") << "v/1\x01garbage that is not an EXR file";
  std::ofstream(dir / "cut.hdr") << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 64 +X 128\n\x02\x02";
  struct Case {
    std::string args;
    std::string expect;  // a piece of the one-line error
  };
  const Case cases[] = {
      {quote(dir / "missing.exr"), "missing.exr: no such file"},
      {quote(dir / "corrupt.exr"), "corrupt.exr: "},
      {quote(dir / "cut.hdr"), "cut.hdr: truncated"},
      {quote(hdriPath("sunset")) + " --size 0", "--size"},
      {quote(hdriPath("sunset")) + " --format rgb565", "--format"},
      {quote(hdriPath("sunset")) + " --size 100 --mips", "power-of-two"},
  };
  for (const Case& c : cases) {
    const CliRun r = runIbl("convert " + c.args + " -o " + quote(dir / "out" / "x.ktx2"));
    EXPECT_NE(r.status, 0) << c.args;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << " -> " << r.output;
    EXPECT_EQ(countFiles(dir / "out"), 0) << c.args;
  }
  const CliRun r =
      runIbl("convert " + quote(hdriPath("sunset")) + " -o " + quote(dir / "out" / "x.jpg"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("unknown output format"), std::string::npos);
}

TEST(Cli, BakeDefaultEnvironment) {
  TempDir dir;
  const CliRun r = runIbl("bake -o " + quote(dir / "out") +
                          " --size 32 --dfg-size 16 --dfg-samples 64 --hdr --layout vcross");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("baked sunset.exr (bundled)"), std::string::npos) << r.output;
  for (const char* f : {"manifest.json", "specular.ktx2", "irradiance.ktx2", "source.ktx2",
                        "dfg.ktx2", "sh.json", "preview.png", "specular_m0.hdr", "irradiance.hdr"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
  const auto bytes = readFileBytes(dir / "out" / "manifest.json");
  const auto m = nlohmann::json::parse(bytes.begin(), bytes.end());
  EXPECT_EQ(m["source"]["path"], "(bundled default: sunset.exr)");
}

TEST(Cli, ShWindowIsRecordedAndAppliedToEveryTarget) {
  // --sh-window cmgen on park (whose exact SH9 irradiance dips below zero): sh.json names the
  // window and its band factors, the coefficients are the exact ones times those factors, and
  // Filament's sh.txt changes with them; --sh-window lanczos applies the fixed factors.
  TempDir dir;
  const std::string base = "bake " + quote(hdriPath("park")) +
                           " --size 32 --dfg-size 16 --dfg-samples 16 --no-preview "
                           "--target ibl,filament -o ";
  ASSERT_EQ(runIbl(base + quote(dir / "exact")).status, 0);
  CliRun r = runIbl(base + quote(dir / "cmgen") + " --sh-window cmgen");
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl(base + quote(dir / "lanczos") + " --sh-window lanczos");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto shJson = [&](const std::string& sub) {
    const auto bytes = readFileBytes(dir / sub / "sh.json");
    return nlohmann::json::parse(bytes.begin(), bytes.end());
  };
  const auto exact = shJson("exact"), cmgen = shJson("cmgen"), lanczos = shJson("lanczos");
  EXPECT_EQ(exact["window"], "off");
  // --help shows the default a bake without the option records (it once showed lanczos).
  const CliRun help = runIbl("bake --help");
  std::smatch shown;
  ASSERT_TRUE(std::regex_search(help.output, shown, std::regex(R"(--sh-window \S*=(\w+))")))
      << help.output;
  EXPECT_EQ(shown[1].str(), exact["window"].get<std::string>());
  EXPECT_EQ(cmgen["window"], "cmgen");
  EXPECT_EQ(lanczos["window"], "lanczos");
  EXPECT_NEAR(lanczos["band_factors"][2].get<double>(), 0.4135, 1e-3);
  const double f1 = cmgen["band_factors"][1], f2 = cmgen["band_factors"][2];
  EXPECT_LT(f2, 0.99);  // park rings: cmgen's window is narrower than its widest
  EXPECT_LT(f2, f1);
  for (int k = 0; k < 9; ++k) {
    const double factor = k == 0 ? 1.0 : k < 4 ? f1 : f2;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(cmgen["coefficients"][k][c].get<double>(),
                  exact["coefficients"][k][c].get<double>() * factor,
                  1e-3 * std::abs(exact["coefficients"][0][c].get<double>()))
          << k;
  }
  const auto shText = [&](const std::string& sub) {
    const auto bytes = readFileBytes(dir / sub / "filament" / "sh.txt");
    return std::string(bytes.begin(), bytes.end());
  };
  EXPECT_NE(shText("exact"), shText("cmgen"));
}

TEST(Cli, BakeFailsCleanly) {
  TempDir dir;
  std::ofstream(dir / "bad.hdr") << "#?RADIANCE\n\n-Y 8 +X 16\n";
  CliRun r = runIbl("bake " + quote(dir / "bad.hdr") + " -o " + quote(dir / "out"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("bad.hdr: truncated"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
  r = runIbl("bake -o " + quote(dir / "out") + " --size 100");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("power of two"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
  EXPECT_EQ(countFiles(dir.path()), 1);  // bad.hdr only: no staging directory
}

TEST(Cli, BakeBytesDoNotDependOnThreads) {
  TempDir dir;
  const std::string args = " --size 32 --dfg-size 16 --dfg-samples 64 --exr --quiet";
  ASSERT_EQ(runIbl("bake -o " + quote(dir / "one") + args + " --threads 1").status, 0);
  ASSERT_EQ(runIbl("bake -o " + quote(dir / "two") + args + " --threads 2").status, 0);
  int compared = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir / "one")) {
    EXPECT_EQ(readFileBytes(e.path()), readFileBytes(dir / "two" / e.path().filename()))
        << e.path();
    ++compared;
  }
  EXPECT_GT(compared, 10);
}

TEST(Cli, RenderAndCompare) {
  TempDir dir;
  // A small bake lights both renders (a render of the default environment bakes it in full).
  CliRun r = runIbl("bake -o " + quote(dir / "bake") +
                    " --size 32 --dfg-size 16 --dfg-samples 64 --no-preview --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string bake = " --bake " + quote(dir / "bake");
  r = runIbl("render sphere -o " + quote(dir / "a.exr") +
             " --size 24x16 --spp 1 --roughness 0.4 --quiet" + bake);
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("render sphere -o " + quote(dir / "b.exr") +
             " --size 24x16 --spp 1 --roughness 0.6 --quiet" + bake);
  ASSERT_EQ(r.status, 0) << r.output;
  const DecodedFile a = readImageFile(dir / "a.exr");
  EXPECT_EQ(a.channels, 4);  // RGB + alpha
  EXPECT_EQ(a.levels[0][0].width, 24);
  r = runIbl("compare " + quote(dir / "a.exr") + " " + quote(dir / "a.exr") + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(nlohmann::json::parse(r.output)["overall"]["rmse"], 0.0);
  r = runIbl("compare " + quote(dir / "a.exr") + " " + quote(dir / "b.exr") +
             " --max-rel-error 1e-6 --error-png " + quote(dir / "err.png"));
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find("exceeds"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "err.png"));
  r = runIbl("render " + quote(dir / "missing.glb") + " -o " + quote(dir / "c.png"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("missing.glb: no such file"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "c.png"));
}

// `ibl compare`'s frame figures on images written here: an 8 x 4 reference of gray 1, the
// judged image 2 in its first 4 x 4 block: frame error 16 / 32, block errors 1 and 0 (median
// 0.5), 16 of 32 pixels off by 2x; the text names them too.
TEST(Cli, CompareReportsTheFrameFigures) {
  TempDir dir;
  Image ref(8, 4, glm::vec3(1.0f)), img(8, 4, glm::vec3(1.0f));
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) img.at(x, y) = glm::vec3(2.0f);
  writeFileAtomic(dir / "ref.exr", encodeExr(ref, ExrPixelType::Float));
  writeFileAtomic(dir / "img.exr", encodeExr(img, ExrPixelType::Float));
  const std::string files = quote(dir / "img.exr") + " " + quote(dir / "ref.exr");
  CliRun r = runIbl("compare " + files + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json frame = nlohmann::json::parse(r.output)["frame"];
  EXPECT_NEAR(frame["frame_error"].get<double>(), 0.5, 1e-6);
  EXPECT_NEAR(frame["median_block_error"].get<double>(), 0.5, 1e-6);
  EXPECT_NEAR(frame["off_by_2x"].get<double>(), 0.5, 1e-12);
  EXPECT_EQ(frame["blocks"], 2);
  r = runIbl("compare " + files);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("frame error 0.5, median 4x4 block error 0.5, off by 2x 50 %"),
            std::string::npos)
      << r.output;
}

// --env none with the bundled lights file (the README's example); a bad lights file is one line
// naming the file and the light, and writes nothing.
TEST(Cli, RenderWithLightsOnly) {
  TempDir dir;
  const std::string lights = quote(dataDir() / "lights" / "studio.json");
  CliRun r = runIbl("render sphere --env none --lights " + lights + " -o " +
                    quote(dir / "lit.exr") + " --size 16x16 --spp 1 --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  const DecodedFile lit = readImageFile(dir / "lit.exr");
  EXPECT_GT(lit.levels[0][0].at(8, 8).x, 0.0f);           // the sphere is lit
  EXPECT_EQ(lit.levels[0][0].at(0, 0), glm::vec3(0.0f));  // on black
  {
    std::ofstream f(dir / "bad.json");
    f << R"({"lights": [{"type": "spot", "position": [0, 1, 0], "intensity": 5, "unit": "lux"}]})";
  }
  r = runIbl("render sphere --env none --lights " + quote(dir / "bad.json") + " -o " +
             quote(dir / "bad.png") + " --size 16x16");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("bad.json: light 0 (spot): missing \"direction\""), std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.png"));
  r = runIbl("render sphere --env none --bake " + quote(dir.path()) + " -o " +
             quote(dir / "c.png"));
  EXPECT_EQ(r.status, 2) << r.output;
}

TEST(Cli, CameraOptionsAreCheckedOrHandled) {
  TempDir dir;
  const std::string base = "render sphere --size 8x8 --spp 1 --quiet -o " + quote(dir / "c.exr");
  // Looking straight down with the default up: another up is picked, the image is complete
  // (lit by nothing: the environment is beside the point).
  CliRun r = runIbl(base + " --look-from 0,10,0 --env none");
  ASSERT_EQ(r.status, 0) << r.output;
  const DecodedFile d = readImageFile(dir / "c.exr");
  EXPECT_EQ(d.levels[0][0].width, 8);
  std::filesystem::remove(dir / "c.exr");
  const std::pair<const char*, const char*> bad[] = {
      {" --look-from 1,2,3 --look-at 1,2,3", "--look-from: equals --look-at"},
      {" --up 0,0,0", "--up: must not be the zero vector"},
      {" --look-from 1e30,0,0", "--look-from: '1e30,0,0' is too far from the origin"},
      {" --look-from nan,0,0", "--look-from: 'nan,0,0' is not finite"},
      {" --camera ortho --ortho-width -2", "--ortho-width: must be positive"}};
  for (const auto& [options, message] : bad) {
    for (const char* mode : {"", " --mode reference"}) {
      r = runIbl(base + options + mode);
      EXPECT_EQ(r.status, 2) << options << mode << ": " << r.output;
      EXPECT_NE(r.output.find(std::string("ibl: error: ") + message), std::string::npos)
          << r.output;
      EXPECT_FALSE(std::filesystem::exists(dir / "c.exr")) << options;
    }
  }
}

// The README's compare example (smaller): the split sum against the reference, both without
// multiple scattering (the single-scattering lobe alone), within the README's 3 %.
TEST(Cli, ReadmeCompareExamplePasses) {
  TempDir dir;
  const std::string common = " --roughness 0.3 --metallic 1 --size 64x64 --background 0,0,0 -q";
  ASSERT_EQ(runIbl("render sphere --mode reference --spp 512 --no-multiscatter -o " +
                   quote(dir / "ref.exr") + common)
                .status,
            0);
  ASSERT_EQ(runIbl("render sphere --spp 64 --no-multiscatter -o " + quote(dir / "rt.exr") + common)
                .status,
            0);
  const CliRun r = runIbl("compare " + quote(dir / "rt.exr") + " " + quote(dir / "ref.exr") +
                          " --max-rel-error 0.03 --json");
  EXPECT_EQ(r.status, 0) << r.output;
}

TEST(Cli, RenderFromAnExistingBake) {
  TempDir dir;
  ASSERT_EQ(
      runIbl("bake -o " + quote(dir / "bake") + " --size 32 --dfg-size 16 --dfg-samples 64 --quiet")
          .status,
      0);
  const CliRun r =
      runIbl("render grid --bake " + quote(dir / "bake") + " -o " + quote(dir / "g.png") +
             " --size 64x32 --spp 1 --tonemap filmic --ev100 2");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("EV100 2.00"), std::string::npos) << r.output;
  EXPECT_EQ(readImageFile(dir / "g.png").levels[0][0].width, 64);
}

// Options that would be ignored, silently changed or meaningless are refused before any work:
// usage errors (CLI11's parse) exit with 2, contradictions found by the command with 1; both
// print one line with the same prefix, and nothing is written.
TEST(Cli, ContradictoryOrMeaninglessOptionsAreErrors) {
  TempDir dir;
  const std::string unlit = "render sphere --env none --size 8x8 --spp 1 -q -o ";
  ASSERT_EQ(runIbl(unlit + quote(dir / "lin.exr")).status, 0);
  ASSERT_EQ(runIbl(unlit + quote(dir / "ldr.png")).status, 0);
  const std::string out = quote(dir / "out");
  const std::string park = quote(hdriPath("park"));
  struct Case {
    std::string args;
    int status;
    std::string message;
  };
  const Case cases[] = {
      {"bake --sizee 3 -o " + out, 2, "ibl: error: unknown option --sizee; did you mean --size?"},
      {"bake --levels 0 -o " + out, 2, "ibl: error: --levels: must be from 1 to 13, not 0"},
      {"bake --levels 13 -o " + out, 2,
       "ibl: error: --levels: 13 levels need a cube of at least 4096^2; --size 256 has 9"},
      {"bake --rotate nan -o " + out, 2, "'nan' is not a finite number"},
      {"bake --clamp inf -o " + out, 2, "'inf' is not a finite number"},
      {"convert " + park + " -o " + quote(dir / "out.exr") + " --exposure 1", 2,
       "out.exr: --exposure applies to PNG outputs only"},
      {"convert " + park + " -o " + quote(dir / "out.exr") + " --rotate inf", 2,
       "'inf' is not a finite number"},
      {"render sphere --env " + park + " --bake " + out + " -o " + quote(dir / "out.png"), 2,
       "ibl: error: --env: contradicts --bake"},
      {"render sphere --camera ortho --ortho-width 0 -o " + quote(dir / "out.png"), 2,
       "ibl: error: --ortho-width: must be positive, not 0"},
      {"render sphere --fov nan -o " + quote(dir / "out.png"), 2, "'nan' is not a finite number"},
      {"render sphere --ev100 nan -o " + quote(dir / "out.png"), 2,
       "ibl: error: --ev100: 'nan' is not finite"},
      {"view sphere --spp 3 --screenshot " + quote(dir / "out.png"), 2,
       "--spp: '3' is not 1, 2, 4 or 8"},
      {"compare " + quote(dir / "lin.exr") + " " + quote(dir / "ldr.png"), 1,
       "lin.exr: is linear radiance but " + (dir / "ldr.png").string() + " is a display image"},
  };
  for (const Case& c : cases) {
    const CliRun r = runIbl(c.args);
    EXPECT_EQ(r.status, c.status) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("ibl: error: ", 0), 0u) << r.output;  // the first line
  }
  EXPECT_EQ(countFiles(dir.path()), 2);  // only the two renders
}

// The manifest prints float parameters as written (0.25, not 0.25000000372529) and names the
// source by an absolute path, whatever the directory the bake ran in.
TEST(Cli, ManifestNumbersAndSourcePath) {
  TempDir dir;
  const CliRun r = runCommand("cd " + quote(dir.path()) + " && cp " + quote(hdriPath("park")) +
                              " park.exr && " + std::string(IBL_CLI) +
                              " bake park.exr -o b --size 32 --levels 6 --dfg-size 16 -q");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::vector<std::uint8_t> bytes = readFileBytes(dir / "b" / "manifest.json");
  const std::string text(bytes.begin(), bytes.end());
  EXPECT_NE(text.find("0.2,"), std::string::npos) << text;  // level 1 of 6: r = 1/5
  EXPECT_EQ(text.find("0.20000000"), std::string::npos);
  const auto j = nlohmann::json::parse(text);
  EXPECT_EQ(j["source"]["path"], (dir / "park.exr").string());
}

// A batch bakes every input into OUTDIR/<name>/; a bad file is reported, the others still
// bake, and the command fails at the end. Inputs come from arguments, patterns and lists.
TEST(Cli, BatchesBakeAndConvertEveryGoodInput) {
  TempDir dir;
  std::filesystem::copy_file(hdriPath("park"), dir / "park.exr");
  std::filesystem::copy_file(hdriPath("night"), dir / "night.exr");
  std::ofstream(dir / "broken.exr") << "not an image";
  CliRun r = runIbl("bake " + quote(dir / "*.exr") + " -o " + quote(dir / "out") +
                    " --size 16 --dfg-size 16 --dfg-samples 64");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("ibl: error: " + (dir / "broken.exr").string() + ": unknown file format"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("2 of 3 inputs done"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 of 3 inputs failed: " + (dir / "broken.exr").string()),
            std::string::npos)
      << r.output;
  for (const char* name : {"park", "night"})
    EXPECT_EQ(readImageFile(dir / "out" / name / "specular.ktx2").levels[0][0].width, 16) << name;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "broken"));
  // A list (comments and blank lines skipped) and convert with {name}.
  std::ofstream(dir / "list.txt") << (dir / "park.exr").string() << "\n# a comment\n\n"
                                  << (dir / "night.exr").string() << "\n";
  r = runIbl("convert --list " + quote(dir / "list.txt") + " -o " +
             quote(dir / "c" / "{name}.hdr") + " --size 32 -q");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(readImageFile(dir / "c" / "park.hdr").levels[0][0].width, 32);
  EXPECT_EQ(readImageFile(dir / "c" / "night.hdr").levels[0][0].width, 32);
  // Two inputs of the same name would write into one place: refused before anything runs.
  std::filesystem::create_directories(dir / "other");
  std::filesystem::copy_file(hdriPath("park"), dir / "other" / "park.exr");
  r = runIbl("bake " + quote(dir / "park.exr") + " " + quote(dir / "other" / "park.exr") + " -o " +
             quote(dir / "dup"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("has the same name 'park'"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "dup"));
  r = runIbl("convert " + quote(dir / "park.exr") + " " + quote(dir / "night.exr") + " -o " +
             quote(dir / "x.ktx2"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("several inputs need {name} in the output"), std::string::npos);
}

// `bake --shard K/N` bakes the batch's inputs whose index (the command line's inputs, then the
// list's lines) is K modulo N; the shards of a batch together write exactly what the batch
// writes in one process, byte for byte (the manifests included: they hold no time).
TEST(Cli, BatchShardsTogetherBakeTheBatchByteForByte) {
  TempDir dir;
  for (const char* name : {"park", "night", "studio"})
    std::filesystem::copy_file(hdriPath(name), dir / (std::string(name) + ".exr"));
  std::ofstream(dir / "list.txt") << (dir / "park.exr").string() << "\n"
                                  << (dir / "studio.exr").string() << "\n";
  // night is index 0 (the command line first), park 1, studio 2.
  const std::string batch = quote(dir / "night.exr") + " --list " + quote(dir / "list.txt") +
                            " --size 8 --dfg-size 8 --dfg-samples 16 --preview-size 8 -q";
  CliRun r = runIbl("bake " + batch + " -o " + quote(dir / "whole"));
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("bake " + batch + " --shard 0/2 -o " + quote(dir / "sharded"));
  ASSERT_EQ(r.status, 0) << r.output;
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir / "sharded"))
    names.insert(e.path().filename().string());
  EXPECT_EQ(names, (std::set<std::string>{"night", "studio"}));
  r = runIbl("bake " + batch + " --shard 1/2 -o " + quote(dir / "sharded"));
  ASSERT_EQ(r.status, 0) << r.output;
  const auto filesUnder = [](const std::filesystem::path& root) {
    std::set<std::string> files;
    for (const auto& e : std::filesystem::recursive_directory_iterator(root))
      if (e.is_regular_file()) files.insert(e.path().lexically_relative(root).string());
    return files;
  };
  const std::set<std::string> whole = filesUnder(dir / "whole");
  EXPECT_EQ(filesUnder(dir / "sharded"), whole);
  EXPECT_EQ(whole.size(), 27u);  // 9 files for each of 3 inputs
  EXPECT_TRUE(whole.count("park/manifest.json"));
  for (const std::string& f : whole)
    EXPECT_EQ(readFileBytes(dir / "sharded" / f), readFileBytes(dir / "whole" / f)) << f;
  // A shard with no input of its own has nothing to do, and says so.
  r = runIbl("bake " + batch + " --shard 3/4 -o " + quote(dir / "none"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "none"));
}

// `ibl info` reads what `ibl convert` reads: six {face} files, and crosses whose padding (here
// a huge value) is not part of the environment's statistics.
TEST(Cli, InfoReadsFacesAndIgnoresCrossPadding) {
  TempDir dir;
  Image cross(16, 12, glm::vec3(1e6f));  // 4 x 3 cells of 4x4; padding cells stay 1e6
  const int cells[6][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}};  // +X -X +Y -Y +Z -Z
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        cross.at(cells[f][0] * 4 + x, cells[f][1] * 4 + y) = glm::vec3(static_cast<float>(f + 1));
  writeFileAtomic(dir / "cross.exr", encodeExr(cross, ExrPixelType::Float));
  CliRun r = runIbl("info --json " + quote(dir / "cross.exr"));
  ASSERT_EQ(r.status, 0) << r.output;
  auto j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["layout"], "hcross");
  EXPECT_EQ(j["max"][0], 6.0);
  EXPECT_NEAR(j["mean"][0].get<double>(), 3.5, 1e-9);  // (1 + ... + 6) / 6
  r = runIbl("convert " + quote(dir / "cross.exr") + " -o " + quote(dir / "f_{face}.exr") +
             " --layout faces --exr-type float -q");
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("info --json " + quote(dir / "f_{face}.exr"));
  ASSERT_EQ(r.status, 0) << r.output;
  j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["faces"], 6);
  EXPECT_EQ(j["layout"], "faces");
  EXPECT_EQ(j["max"][0], 6.0);
  EXPECT_EQ(j["min"][0], 1.0);
  r = runIbl("info " + quote(dir / "f_{face}.png"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("f_px.png: no such file"), std::string::npos) << r.output;
}

// The bake's EXR/HDR copies as equirect panoramas (4n x 2n for an n^2 level) or strips, listed
// in the manifest; a panorama holds the level's power (its integral over the sphere).
TEST(Cli, BakeCopiesAsEquirectOrStrips) {
  TempDir dir;
  CliRun r = runIbl("bake " + quote(hdriPath("park")) + " -o " + quote(dir / "e") +
                    " --size 32 --dfg-size 16 --dfg-samples 64 --exr --layout equirect -q");
  ASSERT_EQ(r.status, 0) << r.output;
  const DecodedFile pano = readImageFile(dir / "e" / "source_m0.exr");
  EXPECT_EQ(pano.levels[0][0].width, 128);
  EXPECT_EQ(pano.levels[0][0].height, 64);
  const DecodedFile cube = readImageFile(dir / "e" / "source.ktx2");
  CubeMap level0;
  level0.levels = {{cube.levels[0][0], cube.levels[0][1], cube.levels[0][2], cube.levels[0][3],
                    cube.levels[0][4], cube.levels[0][5]}};
  const glm::dvec3 a = integrateEquirect(pano.levels[0][0]), b = integrateCube(level0);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c] / b[c], 1.0, 2e-3) << c;  // half floats
  const auto bytes = readFileBytes(dir / "e" / "manifest.json");
  const auto manifest = nlohmann::json::parse(bytes.begin(), bytes.end());
  bool listed = false;
  for (const auto& o : manifest["outputs"])
    if (o["path"] == "source_m0.exr") {
      listed = true;
      EXPECT_EQ(o["layout"], "equirect");
      EXPECT_EQ(o["size"], nlohmann::json({128, 64}));
    }
  EXPECT_TRUE(listed);
  r = runIbl("bake " + quote(hdriPath("park")) + " -o " + quote(dir / "s") +
             " --size 16 --dfg-size 16 --dfg-samples 64 --hdr --layout vstrip -q "
             "--preview-size 20");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(readImageFile(dir / "s" / "preview.png").levels[0][0].width, 120);
  EXPECT_EQ(readImageFile(dir / "s" / "irradiance.hdr").levels[0][0].height, 6 * 32);
}

TEST(Cli, ProbeCapturesBakesAndRendersAndRejectsBadInput) {
  const TempDir dir;
  const auto out = dir.path() / "probe";
  // One probe between the grid's spheres, a box proxy; then a render that reads it.
  // --env none and the lights file: the test is about the plumbing; baking the bundled sky each
  // time is slow under ASan. (Without light a capture is black: refused.)
  const std::string lit = " --env none --lights " + quote(dataDir() / "lights" / "studio.json");
  CliRun r = runIbl("probe grid" + lit +
                    " --at 0,0,0.2 --proxy box:-7,-2,-1,7,2,1 --size 16 --spp 4 -o " + quote(out));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out / "specular.ktx2"));
  EXPECT_TRUE(std::filesystem::exists(out / "coverage_specular.ktx2"));
  EXPECT_TRUE(std::filesystem::exists(out / "coverage_irradiance.ktx2"));
  r = runIbl("render grid --env none --probes " + quote(out) + " --size 32x16 -o " +
             quote(dir.path() / "r.png"));
  ASSERT_EQ(r.status, 0) << r.output;
  // The manifest records the capture's shading; a render of another shading refuses the probe,
  // or with --force warns and renders.
  const nlohmann::json record =
      nlohmann::json::parse(std::ifstream(out / "manifest.json")).at("probe").at("capture");
  EXPECT_EQ(record.at("diffuse"), "disney");
  EXPECT_EQ(record.at("multiscatter"), "walk");
  EXPECT_EQ(record.at("specular_micro_occlusion"), false);
  r = runIbl("render grid --env none --diffuse lambert --probes " + quote(out) +
             " --size 32x16 -o " + quote(dir.path() / "lambert.png"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("captured with another shading (diffuse: disney in the capture, "
                          "lambert here)"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "lambert.png"));
  r = runIbl("render grid --env none --diffuse lambert --force --probes " + quote(out) +
             " --size 32x16 -o " + quote(dir.path() / "lambert.png"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("warning"), std::string::npos) << r.output;
  // --exclude: a name the scene lacks (the built-in grid has none) is a usage error.
  r = runIbl("probe grid" + lit + " --at 0,0,0.2 --size 8 --spp 1 --exclude chair -o " +
             quote(dir.path() / "excluded"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--exclude: no node or mesh of the scene is named 'chair'"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "excluded"));
  // A grid in two shards, merged.
  const auto grid = dir.path() / "grid";
  for (const char* shard : {"0/2", "1/2"}) {
    r = runIbl("probe grid" + lit +
               " --grid 2,1,1 --bounds -3,-1,-0.5,3,1,0.5 --size 8 --spp 2 --shard " +
               std::string(shard) + " -o " + quote(grid));
    ASSERT_EQ(r.status, 0) << r.output;
    if (std::string(shard) == "0/2") {  // half the grid: the merge names what shard 1 owes
      r = runIbl("probe --merge " + quote(grid));
      EXPECT_EQ(r.status, 1) << r.output;
      EXPECT_NE(r.output.find("the shards hold 1 of the grid's 2 probes; missing: probe_1_0_0 "
                              "(owed by shard 1/2, which wrote no probes.shard-1-of-2.json)"),
                std::string::npos)
          << r.output;
      EXPECT_FALSE(std::filesystem::exists(grid / "probes.json"));
    }
  }
  r = runIbl("probe --merge " + quote(grid));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(grid / "probes.json"));
  r = runIbl("render grid --env none --probes " + quote(grid) + " --size 32x16 -o " +
             quote(dir.path() / "g.png"));
  ASSERT_EQ(r.status, 0) << r.output;
  // Bad input: outside the scene, an empty proxy, a folder that holds no probe.
  r = runIbl("probe grid --at 0,0,9 -o " + quote(dir.path() / "x"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("outside the scene's bounds"), std::string::npos) << r.output;
  r = runIbl("probe grid --at 0,0,0 --proxy box:1,1,1,1,2,2 -o " + quote(dir.path() / "x"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("an empty box"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "x"));
  r = runIbl("render grid --probes " + quote(dir.path()) + " -o " + quote(dir.path() / "y.png"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("is not a probe directory"), std::string::npos) << r.output;
}

// A probe inside geometry sees only the inside of a mesh: one probe is an error, a grid leaves
// such probes out, records why in probes.json, and renders never read them. The grid scene's
// spheres (radius 1) sit at x = +-1.25, y = 1.25: of three probes along x in [-1.25, 1.25] at
// y = 1.25, the outer two are inside a sphere, the middle one between them.
TEST(Cli, ProbesInsideGeometryAreRefusedOrLeftOut) {
  TempDir dir;
  CliRun r =
      runIbl("probe grid --env none --at -1.25,1.25,0 --size 8 --spp 1 -o " + quote(dir / "one"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("ibl: error: --at -1.25,1.25,0: the probe is inside geometry: 100 % "
                          "of its rays leave through the back of a face"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "one"));
  r = runIbl("probe grid --env none --lights " + quote(dataDir() / "lights" / "studio.json") +
             " --grid 3,1,1 --bounds -1.25,0.25,-0.5,1.25,2.25,0.5 --size 8 --spp 2 -o " +
             quote(dir / "grid"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("ibl: warning: probe probe_0_0_0 at (-0.833, 1.25, 0) left out: inside "
                          "geometry"),
            std::string::npos)
      << r.output;
  const auto list = nlohmann::json::parse(readFileBytes(dir / "grid" / "probes.json"));
  ASSERT_EQ(list["probes"].size(), 3u);
  for (int i : {0, 2}) {
    EXPECT_NE(list["probes"][i].value("skipped", "").find("inside geometry"), std::string::npos)
        << list.dump();
    EXPECT_FALSE(std::filesystem::exists(dir / "grid" / fmt::format("probe_{}_0_0", i)));
  }
  EXPECT_FALSE(list["probes"][1].contains("skipped"));
  EXPECT_TRUE(std::filesystem::exists(dir / "grid" / "probe_1_0_0" / "manifest.json"));
  r = runIbl("render grid --env none --probes " + quote(dir / "grid") + " --size 16x8 -q -o " +
             quote(dir / "g.png"));
  EXPECT_EQ(r.status, 0) << r.output;
}

// A 2D image that is no environment layout (a table, a rendered frame) converts as an image.
TEST(Cli, ConvertWritesFlatImagesAsImages) {
  TempDir dir;
  ASSERT_EQ(
      runIbl("bake -o " + quote(dir / "b") + " --size 16 --dfg-size 32 --dfg-samples 64 -q").status,
      0);
  CliRun r = runIbl("convert " + quote(dir / "b" / "dfg.ktx2") + " -o " + quote(dir / "dfg.exr") +
                    " --exr-type float");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("a 32x32 image, not an environment"), std::string::npos) << r.output;
  const Image table = readImageFile(dir / "b" / "dfg.ktx2").levels[0][0];
  const Image exr = readImageFile(dir / "dfg.exr").levels[0][0];
  ASSERT_EQ(exr.width, 32);
  ASSERT_EQ(exr.height, 32);
  for (std::size_t i = 0; i < table.pixels.size(); ++i)
    ASSERT_EQ(exr.pixels[i], table.pixels[i]) << i;  // float EXR keeps the half values exactly
  ASSERT_EQ(
      runIbl("render sphere --env none --size 24x24 --spp 1 -q -o " + quote(dir / "r.exr")).status,
      0);
  r = runIbl("convert " + quote(dir / "r.exr") + " -o " + quote(dir / "r.png"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(readImageFile(dir / "r.png").levels[0][0].width, 24);
  // Environment options on an image are an error; a layout named reads it as an environment.
  r = runIbl("convert " + quote(dir / "r.exr") + " -o " + quote(dir / "x.png") + " --size 8");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("apply to environments; the input is a flat image"), std::string::npos);
  r = runIbl("convert " + quote(dir / "r.exr") + " -o " + quote(dir / "x.hdr") +
             " --input-layout mirrorball -q");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(readImageFile(dir / "x.hdr").levels[0][0].width, 48);  // a 2:1 panorama of 24^2
  // A 4:3 frame (a cross's shape) whose cells outside the cross are not empty is a frame; a
  // cross (its gaps black) is read as a cube and written as one.
  ASSERT_EQ(runIbl("render sphere --size 32x24 --spp 1 -q -o " + quote(dir / "f.exr")).status, 0);
  r = runIbl("convert " + quote(dir / "f.exr") + " -o " + quote(dir / "f.png"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("a 32x24 image, not an environment: a cross's shape"), std::string::npos)
      << r.output;
  const Image frame = readImageFile(dir / "f.exr").levels[0][0];
  const Image png = readImageFile(dir / "f.png").levels[0][0];
  ASSERT_EQ(png.width, 32);
  ASSERT_EQ(png.height, 24);
  EXPECT_NEAR(png.at(0, 0).x, std::min(frame.at(0, 0).x, 1.0f), 0.01f);  // read back linear
  ASSERT_EQ(runIbl("convert " + quote(dir / "b" / "source.ktx2") + " -o " +
                   quote(dir / "cross.exr") + " -q")
                .status,
            0);
  ASSERT_EQ(readImageFile(dir / "cross.exr").levels[0][0].width, 64);  // 4:3 of 16^2 faces
  r = runIbl("convert " + quote(dir / "cross.exr") + " -o " + quote(dir / "c.exr"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("not an environment"), std::string::npos) << r.output;
}

// Rendering reads the ibl set: a bake of engine targets only says which target to add.
TEST(Cli, RenderNamesTheTargetABakeLacks) {
  TempDir dir;
  ASSERT_EQ(runIbl("bake -o " + quote(dir / "f") + " --size 16 --target filament -q").status, 0);
  const CliRun r =
      runIbl("render sphere --size 8x8 --bake " + quote(dir / "f") + " -o " + quote(dir / "r.png"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("holds the filament target's files only; rendering reads the ibl set: "
                          "bake again with --target ibl,filament"),
            std::string::npos)
      << r.output;
}

// Damaged pixels through the commands: info lists them, bake warns with their place, convert
// --repair-damage writes a file without them and says how the power changed, and a render of the
// repaired file is no longer tinted by the destroyed sun.
TEST(Cli, DamagedPixelsAreReportedAndRepaired) {
  TempDir dir;
  const std::string damaged = quote(dataDir() / "hdri/damaged/park.exr");
  const CliRun info = runIbl("info " + damaged);
  ASSERT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("damaged     36 pixels in 1 region (x 304-309, y 110-115)"),
            std::string::npos)
      << info.output;
  const CliRun infoJson = runIbl("info --json " + damaged);
  const auto j = nlohmann::json::parse(infoJson.output);
  EXPECT_EQ(j["damaged"]["pixels"], 36);
  EXPECT_EQ(j["damaged"]["regions"][0]["x1"], 309);

  const CliRun bake = runIbl("bake " + damaged + " -o " + quote(dir / "bake") + " --size 16");
  ASSERT_EQ(bake.status, 0) << bake.output;
  EXPECT_NE(bake.output.find("ibl: warning: " + (dataDir() / "hdri/damaged/park.exr").string() +
                             ": 36 pixels in 1 region (x 304-309, y 110-115) damaged"),
            std::string::npos)
      << bake.output;

  const CliRun repaired =
      runIbl("convert " + damaged + " --repair-damage -o " + quote(dir / "park.exr"));
  ASSERT_EQ(repaired.status, 0) << repaired.output;
  EXPECT_NE(repaired.output.find("repaired 36 pixels in 1 region"), std::string::npos)
      << repaired.output;
  EXPECT_NE(repaired.output.find("changed by -"), std::string::npos) << repaired.output;
  const auto k = nlohmann::json::parse(runIbl("info --json " + quote(dir / "park.exr")).output);
  EXPECT_EQ(k["damaged"]["pixels"], 0);
  // The destroyed block held blue up to 11800; what replaced it is its neighbourhood's level.
  EXPECT_LT(k["max"][2].get<double>(), 100.0);
  EXPECT_GT(k["max"][2].get<double>(), 5.0);
  // A sky of computed pixels has none to repair.
  EXPECT_EQ(runIbl("convert sky:elevation=30 --repair-damage -o " + quote(dir / "s.exr")).status,
            2);
}
