// The viewer's window driven as a user drives it: on a virtual X display (Xvfb), xdotool presses
// its keys, drags the mouse and clicks the panel; the window's pixels are read back from the
// display and its title (the settings it shows) from the window, and what changed is checked.
// Under the validation layer, as every GPU test.
#include <cstdlib>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"
#include "support/helpers.hpp"
#include "support/run_command.hpp"
#include "support/text_file.hpp"
#include "support/virtual_display.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

constexpr double kStart = 120.0;  // seconds for the window's first frame (a bake first)
constexpr double kChange = 60.0;  // seconds for a change to show

bool hasTools() {
  return std::system("command -v Xvfb > /dev/null && command -v xdotool > /dev/null") == 0;
}

// The window's title: what the window shows, as `ibl view` words it.
std::string title(const VirtualDisplay& d) {
  return d.xdotool("search --name 'ibl view' getwindowname").output;
}

// Waits until the title contains `text`.
bool titleShows(const VirtualDisplay& d, const std::string& text) {
  return VirtualDisplay::waitFor([&] { return title(d).find(text) != std::string::npos; }, kChange);
}

// The EV100 the title shows (NaN without one).
double titleEv100(const VirtualDisplay& d) {
  std::smatch m;
  const std::string t = title(d);
  return std::regex_search(t, m, std::regex("EV100 (-?[0-9.]+)")) ? std::stod(m[1].str())
                                                                  : std::nan("");
}

// `ibl view` in a window of width x height at the top left of the display, focused, its first
// frame on the screen; run in `folder` when one is given.
void openViewer(VirtualDisplay& d, const std::string& options, int width, int height,
                const std::string& folder = "") {
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  d.launch((folder.empty() ? "" : "cd " + folder + " && ") + std::string(IBL_CLI) + " view " +
           options + " --size " + std::to_string(width) + "x" + std::to_string(height));
  ASSERT_TRUE(d.focusWindow("ibl view", kStart)) << d.log();
  ASSERT_TRUE(titleShows(d, "ms/frame")) << d.log();
  ASSERT_TRUE(
      d.waitForScreen([&](const Screen& s) { return s.mean(0, 0, width, height) > 5.0; }, kChange))
      << d.log();
}

// Clicks the left button at (x, y) as a hand does: the pointer there first, the button held
// over a frame or more (the panel sees a press and a release in separate frames).
void click(const VirtualDisplay& d, int x, int y) {
  d.xdotool("mousemove " + std::to_string(x) + " " + std::to_string(y) +
            " sleep 1 mousedown 1 sleep 1 mouseup 1");
}

// Closes the viewer with Q: it exits with status 0, saying so.
void closeViewer(VirtualDisplay& d) {
  d.xdotool("key q");
  EXPECT_EQ(d.exitStatus(kChange), 0) << d.log();
  EXPECT_NE(d.log().find("viewed "), std::string::npos) << d.log();
  EXPECT_EQ(d.log().find("vulkan validation"), std::string::npos) << d.log();
}

}  // namespace

// Every key of the window's footer, pressed: the exposure brightens and darkens the frame, the tone
// curve, the terms and the view change what the title says, a drag orbits the camera and R
// brings it back to the same pixels, F1 shows and hides the panel, V shows the buffers, the right
// button picks a surface, Q closes the window.
TEST(ViewerWindow, KeysChangeWhatTheWindowShows) {
  ASSERT_TRUE(hasTools()) << "Xvfb or xdotool missing: run scripts/setup.sh";
  VirtualDisplay d(320, 240);
  const int w = 200, h = 150;
  openViewer(d, "sphere --panel off --ev100 1 --bloom off --spp 1", w, h);
  const auto brightness = [&](const Screen& s) { return s.mean(0, 0, w, h); };
  const Screen start = d.screen();
  d.xdotool("key equal");  // + : half a stop brighter
  EXPECT_TRUE(d.waitForScreen(
      [&](const Screen& s) { return brightness(s) > brightness(start) + 4.0; }, kChange));
  d.xdotool("key minus minus");  // - twice: half a stop darker than at the start
  EXPECT_TRUE(d.waitForScreen(
      [&](const Screen& s) { return brightness(s) < brightness(start) - 4.0; }, kChange));
  EXPECT_TRUE(titleShows(d, "EV100 1.5"));
  d.xdotool("key equal");
  EXPECT_TRUE(titleShows(d, "EV100 1.0"));
  d.xdotool("key t");
  EXPECT_TRUE(titleShows(d, "filmic"));
  d.xdotool("key t");
  EXPECT_TRUE(titleShows(d, "no tone curve"));
  d.xdotool("key t");
  EXPECT_TRUE(titleShows(d, "ACES"));
  // The diffuse term off: the sphere's middle darkens.
  const Screen lit = d.screen();
  d.xdotool("key d");
  EXPECT_TRUE(titleShows(d, "specular only"));
  EXPECT_TRUE(d.waitForScreen(
      [&](const Screen& s) {
        return s.mean(w / 2 - 10, h / 2 - 10, w / 2 + 10, h / 2 + 10) <
               lit.mean(w / 2 - 10, h / 2 - 10, w / 2 + 10, h / 2 + 10) - 20.0;
      },
      kChange));
  d.xdotool("key d");
  EXPECT_TRUE(titleShows(d, "diffuse + specular"));
  ASSERT_TRUE(d.waitForScreen([&](const Screen& s) { return s.difference(lit, 0, 0, w, h) < 0.5; },
                              kChange));
  // A drag to the right orbits the camera (the environment behind moves); R resets the view.
  d.xdotool("mousemove 100 75 mousedown 1 mousemove 160 80 mouseup 1");
  EXPECT_TRUE(d.waitForScreen([&](const Screen& s) { return s.difference(lit, 0, 0, w, h) > 5.0; },
                              kChange));
  d.xdotool("key r");
  EXPECT_TRUE(d.waitForScreen([&](const Screen& s) { return s.difference(lit, 0, 0, w, h) < 0.5; },
                              kChange));
  // The wheel zooms in: the sphere fills more of the frame, its rim moves past the corner's pixels.
  d.xdotool("mousemove 100 75 click 4 click 4 click 4");
  EXPECT_TRUE(d.waitForScreen([&](const Screen& s) { return s.difference(lit, 0, 0, w, h) > 5.0; },
                              kChange))
      << d.screen().difference(lit, 0, 0, w, h) << " " << title(d);
  d.xdotool("key r");
  EXPECT_TRUE(d.waitForScreen([&](const Screen& s) { return s.difference(lit, 0, 0, w, h) < 0.5; },
                              kChange));
  // F1: the panel over the top left; again: gone.
  d.xdotool("key F1");
  EXPECT_TRUE(d.waitForScreen(
      [&](const Screen& s) { return s.difference(lit, 0, 0, w / 2, h / 2) > 20.0; }, kChange));
  d.xdotool("key F1");
  EXPECT_TRUE(d.waitForScreen([&](const Screen& s) { return s.difference(lit, 0, 0, w, h) < 0.5; },
                              kChange));
  // V: the buffers, the first the base color as it is (the sphere's white, the background black);
  // twelve more come round to the shading.
  d.xdotool("key v");
  EXPECT_TRUE(titleShows(d, "buffer base-color"));
  EXPECT_TRUE(d.waitForScreen(
      [&](const Screen& s) {
        return s.mean(w / 2 - 10, h / 2 - 10, w / 2 + 10, h / 2 + 10) > 250.0 &&
               s.mean(0, 0, 10, 10) < 1.0;
      },
      kChange));
  d.xdotool("key v v v v v v v v v v v v");
  EXPECT_TRUE(d.waitForScreen([&](const Screen& s) { return s.difference(lit, 0, 0, w, h) < 0.5; },
                              kChange));
  // [ and ]: the skybox's mip level; M: the reference view, traced on the device.
  d.xdotool("key bracketright");
  EXPECT_TRUE(titleShows(d, "skybox mip 0.5"));
  d.xdotool("key bracketleft m");
  EXPECT_TRUE(titleShows(d, "reference: "));
  // The right button picks the surface under the cursor: the sphere's white dielectric of
  // roughness 0.5, facing the camera, reported on stderr (and in the panel).
  d.xdotool("mousemove 100 75 click 3");
  closeViewer(d);
  EXPECT_NE(d.log().find("(reference view at the end)"), std::string::npos) << d.log();
  for (const char* fact : {"ibl view: picked pixel (100, 75)", ": sphere 0; material 0;",
                           "base color 1.000, 1.000, 1.000 (linear)",
                           "metallic 0.000, roughness 0.500", "shading normal 0."})
    EXPECT_NE(d.log().find(fact), std::string::npos) << fact << "\n" << d.log();
}

// A file dropped on the window (by the XDND protocol, as a file manager drops it:
// support/xdnd_drop.cpp) relights the scene: the night sky after the default environment, at the
// same exposure, darkens the frame, and stderr names the file. A file that is no environment is
// one line on stderr, and the window goes on.
TEST(ViewerWindow, ADroppedEnvironmentRelightsTheScene) {
  ASSERT_TRUE(hasTools()) << "Xvfb or xdotool missing: run scripts/setup.sh";
  VirtualDisplay d(320, 240);
  const int w = 160, h = 120;
  openViewer(d, "sphere --panel off --ev100 1 --bloom off --spp 1", w, h);
  const Screen before = d.screen();
  std::string window = d.xdotool("search --name 'ibl view'").output;
  window = window.substr(0, window.find('\n'));
  const auto dropFile = [&](const std::filesystem::path& file) {
    return d.onDisplay(std::string(IBL_XDND_DROP) + " " + window + " " + quote(file));
  };
  const CliRun dropped = dropFile(std::filesystem::absolute(hdriPath("night")));
  EXPECT_EQ(dropped.status, 0) << dropped.output;
  EXPECT_TRUE(d.waitFor(
      [&] { return d.log().find("ibl view: night.exr: new environment") != std::string::npos; },
      kChange))
      << d.log();
  EXPECT_TRUE(d.waitForScreen(
      [&](const Screen& s) { return s.mean(0, 0, w, h) < before.mean(0, 0, w, h) - 10.0; },
      kChange))
      << d.log();
  const TempDir dir;
  const auto bad = dir / "notes.exr";
  std::ofstream(bad) << "not an image";
  EXPECT_EQ(dropFile(bad).status, 0);
  EXPECT_TRUE(d.waitFor([&] { return d.log().find("notes.exr") != std::string::npos; }, kChange))
      << d.log();
  EXPECT_TRUE(titleShows(d, "ms/frame"));  // still drawing
  closeViewer(d);
}

// Auto exposure follows the light: the sphere alone on black (a black background is not
// metered), its diffuse term switched off, gets 3 or more stops darker; the window's exposure
// settles on what `ibl view --screenshot` meters for that frame (the same histogram rule), and the
// sphere comes back to about its brightness. With A (auto exposure off) the same change stays dark.
TEST(ViewerWindow, AutoExposureFollowsTheLight) {
  ASSERT_TRUE(hasTools()) << "Xvfb or xdotool missing: run scripts/setup.sh";
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);  // the Vulkan driver's, under the sanitizers
  const std::string scene = "sphere --background 0,0,0 --bloom off --spp 1 --roughness 0.3 ";
  const int w = 160, h = 120;
  const CliRun shot = runCommand(std::string(IBL_CLI) + " view " + scene +
                                 "--only specular --size 160x120 --screenshot " +
                                 (testing::TempDir() + "/auto-exposure.png"));
  ASSERT_EQ(shot.status, 0) << shot.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(shot.output, m, std::regex("EV100 (-?[0-9.]+)"))) << shot.output;
  const double specularEv100 = std::stod(m[1].str());

  VirtualDisplay d(320, 240);
  openViewer(d, scene + "--panel off --adaptation-speed 20", w, h);
  const double litEv100 = titleEv100(d);
  EXPECT_GT(litEv100 - specularEv100, 2.0);  // the diffuse term is most of the sphere's light
  const Screen lit = d.screen();
  const auto middle = [&](const Screen& s) {
    return s.mean(w / 2 - 15, h / 2 - 15, w / 2 + 15, h / 2 + 15);
  };
  d.xdotool("key d");
  EXPECT_TRUE(VirtualDisplay::waitFor(
      [&] { return std::abs(titleEv100(d) - specularEv100) < 0.15; }, kChange))
      << title(d) << " against " << specularEv100;
  // Settled: the metered exposure brings the sphere back near its brightness (the specular term
  // has its own pattern: a loose bound).
  EXPECT_TRUE(d.waitForScreen(
      [&](const Screen& s) { return std::abs(middle(s) - middle(lit)) < 0.35 * middle(lit); },
      kChange));
  // Auto exposure off (A), the diffuse term back on: the exposure stays, the sphere is far
  // brighter than it was.
  d.xdotool("key a d");
  EXPECT_TRUE(titleShows(d, "diffuse + specular"));
  EXPECT_TRUE(
      d.waitForScreen([&](const Screen& s) { return middle(s) > 1.5 * middle(lit); }, kChange));
  EXPECT_NEAR(titleEv100(d), specularEv100, 0.15);
  closeViewer(d);
}

// The panel's controls, clicked where Dear ImGui lays them out (the panel at the top left, 360
// pixels wide, its default font and style): the diffuse check box, the compensation slider's
// right end (+6 stops) and the tone curve's menu.
TEST(ViewerWindow, PanelControlsChangeTheFrame) {
  ASSERT_TRUE(hasTools()) << "Xvfb or xdotool missing: run scripts/setup.sh";
  VirtualDisplay d(640, 480);
  const int w = 560, h = 420;
  openViewer(d, "sphere --ev100 1 --bloom off --spp 1", w, h);
  // The panel is drawn: its title bar's blue over the frame.
  ASSERT_TRUE(d.waitForScreen(
      [&](const Screen& s) {
        return s.rgb[3 * (5 * s.width + 150) + 2] > s.rgb[3 * (5 * s.width + 150)] + 40;
      },
      kChange));
  click(d, 17, 323);  // "diffuse"
  EXPECT_TRUE(titleShows(d, "specular only")) << title(d);
  click(d, 17, 323);
  EXPECT_TRUE(titleShows(d, "diffuse + specular")) << title(d);
  const Screen before = d.screen();
  click(d, 214, 185);  // "compensation" near its right end (+5 stops)
  EXPECT_TRUE(VirtualDisplay::waitFor([&] { return titleEv100(d) < -3.0; }, kChange)) << title(d);
  EXPECT_TRUE(d.waitForScreen(
      [&](const Screen& s) {
        return s.mean(400, 100, 500, 300) > before.mean(400, 100, 500, 300) + 20.0;
      },
      kChange));
  click(d, 110, 208);                                  // "tone curve": its menu opens below
  VirtualDisplay::waitFor([] { return false; }, 2.0);  // a frame or more to open it
  click(d, 60, 228);                                   // its first item, "none"
  EXPECT_TRUE(titleShows(d, "no tone curve")) << title(d);
  closeViewer(d);
}

// What the window shows, saved by the panel's "save settings" after the keys and a drag changed
// it (exposure compensation, tone curve, camera; auto exposure settled, then switched off, so
// that the file holds its EV100; the window's size), is what `ibl view --settings FILE
// --screenshot` renders: the window's pixels beside the panel and the screenshot's agree within
// a code value of 8-bit sRGB on average.
TEST(ViewerWindow, SavedSettingsReproduceTheWindowInAScreenshot) {
  ASSERT_TRUE(hasTools()) << "Xvfb or xdotool missing: run scripts/setup.sh";
  TempDir dir;
  VirtualDisplay d(640, 480);
  const int w = 480, h = 400;
  const std::string scene = "sphere --spp 1 --bloom off --roughness 0.3 ";
  openViewer(d, scene + "--adaptation-speed 20", w, h, dir.path().string());
  const Screen start = d.screen();
  d.xdotool("key equal t");
  d.xdotool("mousemove 400 100 mousedown 1 mousemove 440 120 mouseup 1");
  ASSERT_TRUE(titleShows(d, "filmic"));
  ASSERT_TRUE(d.waitForScreen(
      [&](const Screen& s) { return s.difference(start, 370, 0, w, h) > 5.0; }, kChange));
  VirtualDisplay::waitFor([] { return false; }, 3.0);  // auto exposure settles
  d.xdotool("key a");                                  // then stays: the file holds that EV100
  VirtualDisplay::waitFor([] { return false; }, 1.0);
  click(d, 165, 369);  // "save settings"
  const auto saved = dir / "ibl_view_settings_001.json";
  ASSERT_TRUE(VirtualDisplay::waitFor([&] { return std::filesystem::exists(saved); }, kChange))
      << d.log();
  const Screen window = d.screen();
  closeViewer(d);
  const std::string json = readText(saved);
  EXPECT_NE(json.find("\"exposure_compensation\": 0.5"), std::string::npos) << json;
  EXPECT_NE(json.find("\"tonemap\": \"filmic\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"auto_exposure\": false"), std::string::npos) << json;
  EXPECT_NE(json.find("\"ev100\": "), std::string::npos) << json;
  EXPECT_NE(json.find("\"size\": \"480x400\""), std::string::npos) << json;
  // The drag turned the camera off the scene's axis (the sphere's default view is along z).
  std::smatch from;
  ASSERT_TRUE(std::regex_search(json, from, std::regex("\"look_from\": \\[\\s*(-?[0-9.e+-]+)")))
      << json;
  EXPECT_GT(std::abs(std::stod(from[1].str())), 0.1) << json;

  const auto shot = dir / "shot.png";
  const CliRun r =
      runIbl("view " + scene + "--settings " + quote(saved) + " --screenshot " + quote(shot));
  ASSERT_EQ(r.status, 0) << r.output;
  const Image image = readImageFile(shot).levels[0][0];
  ASSERT_EQ(image.width, w);
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 370; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        sum += std::abs(int(linearToSrgb8(image.at(x, y)[c])) -
                        int(window.rgb[3 * (static_cast<std::size_t>(y) * window.width + x) + c]));
        ++count;
      }
  EXPECT_LT(sum / count, 1.0);
  // Without the settings the screenshot is another picture.
  const CliRun plain =
      runIbl("view " + scene + "--size 480x400 --screenshot " + quote(dir / "plain.png"));
  ASSERT_EQ(plain.status, 0) << plain.output;
  const Image other = readImageFile(dir / "plain.png").levels[0][0];
  double apart = 0.0;
  for (std::size_t i = 0; i < other.pixels.size(); ++i)
    apart += std::abs(luminance(other.pixels[i]) - luminance(image.pixels[i]));
  EXPECT_GT(apart / static_cast<double>(other.pixels.size()), 0.02);
}

// --settings FILE with options of its own: the command line wins setting by setting (here the
// compensation, then the exposure), the file gives the rest; the screenshots equal those of the
// same settings given as options, pixel for pixel.
TEST(ViewerSettings, TheCommandLineWinsOverTheFile) {
  TempDir dir;
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  CliRun r = runIbl("bake -o " + quote(dir / "bake") +
                    " --size 64 --dfg-size 16 --dfg-samples 64 --no-preview -q");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string same =
      "view sphere --size 32x24 --spp 1 --bloom off -q --bake " + quote(dir / "bake") + " ";
  const auto settings = dir / "settings.json";
  std::ofstream(settings) << R"({"exposure_compensation": 1, "tonemap": "filmic",
                                 "auto_exposure": false, "ev100": 2})";
  const auto shot = [&](const std::string& name, const std::string& options) {
    const CliRun run = runIbl(same + options + " --screenshot " + quote(dir / name));
    EXPECT_EQ(run.status, 0) << run.output;
    return readImageFile(dir / name).levels[0][0].pixels;
  };
  const auto fromFile = shot("a.png", "--settings " + quote(settings));
  EXPECT_TRUE(fromFile == shot("b.png", "--tonemap filmic --exposure-compensation 1 --ev100 2"));
  const auto noCompensation =
      shot("c.png", "--settings " + quote(settings) + " --exposure-compensation 0");
  EXPECT_TRUE(noCompensation == shot("d.png", "--tonemap filmic --ev100 2"));
  EXPECT_FALSE(noCompensation == fromFile);
  const auto otherExposure = shot("e.png", "--settings " + quote(settings) + " --ev100 4");
  EXPECT_TRUE(otherExposure ==
              shot("f.png", "--tonemap filmic --exposure-compensation 1 --ev100 4"));
  EXPECT_FALSE(otherExposure == fromFile);
  // A buffer from the file, and the command line's shading over it.
  const auto buffered = dir / "buffered.json";
  std::ofstream(buffered) << R"({"buffer": "normals", "tonemap": "filmic"})";
  const auto normals = shot("g.png", "--settings " + quote(buffered));
  EXPECT_TRUE(normals == shot("h.png", "--buffer normals"));
  EXPECT_TRUE(shot("i.png", "--settings " + quote(buffered) + " --buffer shaded") ==
              shot("j.png", "--tonemap filmic"));
}
