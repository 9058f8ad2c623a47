// `ibl view`: the real-time viewer (Vulkan), in a window or headless to a screenshot.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "ibl/core/error.hpp"
#include "ibl/env/photometry.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/gpu/path_tracer.hpp"
#include "ibl/gpu/viewer.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/json_file.hpp"
#include "ibl/render/bloom.hpp"
#include "ibl/render/exposure.hpp"
#include "ibl/render/irradiance_volume.hpp"
#include "ibl/render/light.hpp"
#include "ibl/shared/temporal_antialiasing.h"
#include "preflight.hpp"
#include "scene_options.hpp"

namespace ibl::cli {

namespace {

// The bloom unless --bloom says otherwise, of the screenshots and the live window: light 3 stops
// above the average luminance the exposure is set for spreads.
constexpr float kViewBloom = 3.0f;

struct ViewCliOptions {
  SceneCliOptions scene;
  std::string screenshot;
  int frames = 0;
  float skyboxMip = 0.0f;
  std::string reference;  // the view: reference, difference or split (empty: real time)
  std::optional<int> referenceSpp;
  std::string volumeUpdate;  // on or off (empty: on)
  std::string autoExposure;  // on or off (empty: on without --ev100 or camera settings)
  std::string metering = "10,90";
  float adaptationSpeed = 3.0f;
  std::string panel = "on";
  std::string settings;           // --settings FILE
  std::string buffer = "shaded";  // --buffer NAME (gpu::bufferViewName)
  std::string clay = "off";       // --clay on|off
  std::string taa;                // --taa on|off|N (empty: on in the window, off in screenshots)
  float split = 0.5f;             // --split: the split view's boundary, a share of the width
};

// The most frames --taa N accumulates.
constexpr int kMaxTaaFrames = 4096;

// --taa for a screenshot: the jittered frames it averages (0: one frame, unjittered); for the
// window, whether temporal antialiasing starts on (any value but off).
int taaFrames(const ViewCliOptions& o) {
  if (o.taa.empty() || o.taa == "off") return 0;
  if (o.taa == "on") return shared::kTemporalJitterPeriod;
  int frames = 0;
  std::size_t used = 0;
  try {
    frames = std::stoi(o.taa, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != o.taa.size() || frames < 1 || frames > kMaxTaaFrames)
    failUsage("--taa",
              fmt::format("{}: wants on, off, or the frames a screenshot averages, 1 to {}", o.taa,
                          kMaxTaaFrames));
  return frames;
}

// Whether the exposure is fixed by --ev100 or --aperture, --shutter and --iso.
bool fixedExposure(const SceneCliOptions& o) {
  return !o.ev100.empty() || (o.aperture > 0 && o.shutter > 0 && o.iso > 0);
}

// --metering LOW,HIGH: the percentiles auto exposure meters between.
MeteringRange meteringRange(const ViewCliOptions& o) {
  const std::vector<float> p = parseNumbers(o.metering, 2, "--metering");
  if (!(p[0] >= 0.0f && p[0] < p[1] && p[1] <= 100.0f))
    failUsage(
        "--metering",
        fmt::format("{}: wants two percentiles LOW,HIGH with 0 <= LOW < HIGH <= 100", o.metering));
  return {p[0], p[1]};
}

// The exposure of a view's picture: fixed by the options, or metered as the window's auto
// exposure meters a frame (the histogram between the --metering percentiles).
float viewEv100(const ViewCliOptions& o, const Image& linear) {
  return fixedExposure(o.scene) ? chooseEv100(o.scene, linear)
                                : meteredEv100(luminanceHistogram(linear), meteringRange(o),
                                               chooseEv100(o.scene, linear));
}

// The reference's samples per pixel of a screenshot unless --reference-spp says otherwise.
constexpr int kScreenshotReferenceSpp = 64;
// The reference's samples per dispatch of a screenshot (a device may stop a long one).
constexpr int kScreenshotReferenceBatch = 16;

// --volume-update-frames N: the volume's live update run N frames on the device before a
// screenshot, timed.
void updateVolumeBeforeScreenshot(gpu::SceneRenderer& renderer, const Camera& camera,
                                  const RenderOptions& shading, const SceneCliOptions& o,
                                  const GlobalOptions& global) {
  if (o.volumeUpdateFrames <= 0) return;
  const auto start = std::chrono::steady_clock::now();
  renderer.updateVolume(camera, shading, o.volumeUpdateFrames);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!global.quiet)
    fmt::print(stderr, "volume updated over {} frames in {:.2f} s ({:.1f} ms per frame on {})\n",
               o.volumeUpdateFrames, seconds, 1000.0 * seconds / o.volumeUpdateFrames,
               renderer.context().device().name);
}

gpu::ViewMode viewMode(const std::string& name) {
  return name == "reference"    ? gpu::ViewMode::Reference
         : name == "difference" ? gpu::ViewMode::Difference
         : name == "split"      ? gpu::ViewMode::Split
                                : gpu::ViewMode::RealTime;
}

// A screenshot of `view`: the difference view's false colors and a buffer's colors as they are
// (a PNG as `ibl compare --error-png` writes it; an EXR of the same values and the coverage), the
// others bloomed when asked and written like `ibl render`'s images.
void writeView(const std::string& path, RenderResult shown, gpu::ViewMode view,
               gpu::BufferView buffer, float ev100, ToneMap curve, const SceneCliOptions& scene) {
  if (view == gpu::ViewMode::Difference || buffer != gpu::BufferView::Shaded) {
    checkRenderedImagePath(path);
    if (fileFormatFromExtension(path) == FileFormat::Exr)
      writeFileAtomic(path, encodeExr(shown.color, ExrPixelType::Float, &shown.alpha));
    else
      writeFileAtomic(path, encodePng(shown.color));
    return;
  }
  if (const std::optional<float> bloom = bloomCompensation(scene, kViewBloom))
    shown.color = applyBloom(shown.color, ev100, *bloom);
  writeRenderedImage(path, shown, ev100, curve, false);
}

// ibl_view_001.png, 002, ... (stem "ibl_view", extension ".png"): the first name not taken in
// the working directory.
std::string unusedName(const char* stem, const char* extension) {
  for (int n = 1;; ++n) {
    std::string name = fmt::format("{}_{:03}{}", stem, n, extension);
    if (!std::filesystem::exists(name)) return name;
  }
}

const char* toneMapOption(ToneMap t) {
  return t == ToneMap::None ? "none" : t == ToneMap::Filmic ? "filmic" : "aces";
}

// The settings file's keys and the options they stand for (the command line's wins).
struct SettingKey {
  const char* key;
  const char* option;
};
constexpr SettingKey kSettingKeys[] = {
    {"size", "--size"},         {"look_from", "--look-from"},
    {"look_at", "--look-at"},   {"up", "--up"},
    {"fov", "--fov"},           {"auto_exposure", "--auto-exposure"},
    {"ev100", "--ev100"},       {"adaptation_speed", "--adaptation-speed"},
    {"metering", "--metering"}, {"exposure_compensation", "--exposure-compensation"},
    {"tonemap", "--tonemap"},   {"bloom", "--bloom"},
    {"only", "--only"},         {"skybox_mip", "--skybox-mip"},
    {"view", "--reference"},    {"buffer", "--buffer"},
    {"clay", "--clay"},         {"panel", "--panel"},
    {"taa", "--taa"},           {"split", "--split"},
};

// The settings file the panel saves and --settings reads: what the window shows, each setting
// under its key of kSettingKeys.
std::string settingsJson(const gpu::ViewSettings& v) {
  // Each float as its shortest decimal (0.3f as 0.3, not as the double 0.30000001192092896).
  const auto num = [](float x) { return std::stod(fmt::format("{}", x)); };
  const auto vec = [&](glm::vec3 p) {
    return nlohmann::json::array({num(p.x), num(p.y), num(p.z)});
  };
  nlohmann::ordered_json j;
  j["size"] = fmt::format("{}x{}", v.width, v.height);
  j["look_from"] = vec(v.from);
  j["look_at"] = vec(v.at);
  j["up"] = vec(v.up);
  if (v.perspective) j["fov"] = num(v.fov);
  j["auto_exposure"] = !v.ev100.has_value();
  if (v.ev100) j["ev100"] = num(*v.ev100);
  j["adaptation_speed"] = num(v.adaptationSpeed);
  j["metering"] = {num(v.metering.low), num(v.metering.high)};
  j["exposure_compensation"] = num(v.compensation);
  j["tonemap"] = toneMapOption(v.toneMap);
  j["bloom"] = v.bloom ? nlohmann::json(num(*v.bloom)) : nlohmann::json("off");
  j["only"] = v.only == ShadingTerms::Diffuse    ? "diffuse"
              : v.only == ShadingTerms::Specular ? "specular"
                                                 : "both";
  j["skybox_mip"] = num(v.skyboxLod);
  j["view"] = v.view == gpu::ViewMode::RealTime ? "real-time" : gpu::viewModeName(v.view);
  j["split"] = num(v.split);
  j["buffer"] = gpu::bufferViewName(v.buffer);
  j["clay"] = v.clay;
  j["taa"] = v.temporalAntialiasing;
  j["panel"] = v.panel;
  return j.dump(2) + "\n";
}

// --settings FILE: each setting of the file taken as its option, unless the command line gives
// that option (the command line wins; a fixed exposure there overrides the file's exposure).
// Values are checked as their options check them; a mistake names the file and the setting.
void applySettingsFile(ViewCliOptions& o) {
  if (o.settings.empty()) return;
  const nlohmann::json j = readJsonFile(o.settings);
  const auto bad = [&](const std::string& key, const std::string& problem) {
    fail(o.settings, fmt::format("\"{}\" {}", key, problem));
  };
  if (!j.is_object()) fail(o.settings, "is not a JSON object of settings");
  const auto number = [&](const std::string& key, double lo, double hi) {
    if (!j[key].is_number()) bad(key, "must be a number");
    const double v = j[key].get<double>();
    if (!(v >= lo && v <= hi)) bad(key, fmt::format("must be from {} to {}, not {}", lo, hi, v));
    return static_cast<float>(v);
  };
  const auto text = [&](const std::string& key, std::initializer_list<const char*> allowed) {
    if (!j[key].is_string()) bad(key, "must be a string");
    const std::string value = j[key].get<std::string>();
    std::string list;
    for (const char* a : allowed) {
      if (value == a) return value;
      list += (list.empty() ? "" : ", ") + std::string(a);
    }
    bad(key, fmt::format("must be one of {}, not \"{}\"", list, value));
    return value;
  };
  const auto numbers = [&](const std::string& key, std::size_t count, const char* shape) {
    if (!j[key].is_array() || j[key].size() != count) bad(key, fmt::format("must be {}", shape));
    std::string joined;
    for (const auto& c : j[key]) {
      if (!c.is_number() || !std::isfinite(c.get<double>()))
        bad(key, fmt::format("must be {}", shape));
      joined += (joined.empty() ? "" : ",") + fmt::format("{}", c.get<double>());
    }
    return joined;
  };
  const auto boolean = [&](const std::string& key) {
    if (!j[key].is_boolean()) bad(key, "must be true or false");
    return j[key].get<bool>() ? std::string("on") : std::string("off");
  };
  const bool exposureGiven = given(o.scene, "--ev100") || given(o.scene, "--aperture") ||
                             given(o.scene, "--shutter") || given(o.scene, "--iso") ||
                             given(o.scene, "--auto-exposure");
  for (const auto& [key, value] : j.items()) {
    const SettingKey* setting = nullptr;
    for (const SettingKey& s : kSettingKeys)
      if (key == s.key) setting = &s;
    if (!setting) fail(o.settings, fmt::format("unknown setting \"{}\"", key));
    const bool exposure = key == "ev100" || key == "auto_exposure";
    if (exposure ? exposureGiven : given(o.scene, setting->option)) continue;
    if (key == "size") {
      if (!value.is_string()) bad(key, "must be a string WIDTHxHEIGHT");
      o.scene.size = value.get<std::string>();  // checked as --size is
    }
    if (key == "look_from") o.scene.lookFrom = numbers(key, 3, "[x, y, z]");
    if (key == "look_at") o.scene.lookAt = numbers(key, 3, "[x, y, z]");
    if (key == "up") o.scene.up = numbers(key, 3, "[x, y, z]");
    if (key == "fov") o.scene.fov = number(key, 1.0, 179.0);
    if (key == "ev100") o.scene.ev100 = fmt::format("{}", number(key, -30.0, 40.0));
    if (key == "auto_exposure") o.autoExposure = boolean(key);
    if (key == "adaptation_speed") o.adaptationSpeed = number(key, 0.0, 1000.0);
    if (key == "metering") o.metering = numbers(key, 2, "[low, high] percentiles");
    if (key == "exposure_compensation") o.scene.compensation = number(key, -30.0, 30.0);
    if (key == "tonemap") o.scene.tonemap = text(key, {"aces", "filmic", "none"});
    if (key == "bloom")
      o.scene.bloom =
          value.is_string() ? text(key, {"off"}) : fmt::format("{}", number(key, -30.0, 30.0));
    if (key == "only") {
      o.scene.only = text(key, {"both", "diffuse", "specular"});
      if (o.scene.only == "both") o.scene.only.clear();
    }
    if (key == "skybox_mip") o.skyboxMip = number(key, 0.0, 16.0);
    if (key == "view") {
      o.reference = text(key, {"real-time", "reference", "difference", "split"});
      if (o.reference == "real-time") o.reference.clear();
    }
    if (key == "buffer") {
      if (!value.is_string() || !gpu::bufferViewNamed(value.get<std::string>()))
        bad(key, "must be a buffer's name (ibl view --help lists them)");
      o.buffer = value.get<std::string>();
    }
    if (key == "clay") o.clay = boolean(key);
    if (key == "taa") o.taa = boolean(key);
    if (key == "split") o.split = number(key, 0.0, 1.0);
    if (key == "panel") o.panel = boolean(key);
  }
  // A buffer and clay belong to the real-time view: a comparison view on the command line leaves
  // the file's out, either of them there the file's comparison view; both in the file contradict.
  if (!o.reference.empty() && (o.buffer != "shaded" || o.clay == "on")) {
    const bool viewGiven = given(o.scene, "--reference");
    const bool bufferGiven = given(o.scene, "--buffer"), clayGiven = given(o.scene, "--clay");
    // The command line asks for the real-time view only with a buffer or clay turned on.
    const bool realTimeGiven =
        (bufferGiven && o.buffer != "shaded") || (clayGiven && o.clay == "on");
    if (viewGiven) {
      if (!bufferGiven) o.buffer = "shaded";
      if (!clayGiven) o.clay = "off";
    } else if (realTimeGiven) {
      o.reference.clear();
    } else {
      bad(o.buffer != "shaded" ? "buffer" : "clay",
          fmt::format("shows the real-time frame, not the \"{}\" view", o.reference));
    }
  }
  // The file's fixed exposure: its auto_exposure (true when saved with auto exposure on, then
  // without an ev100) says nothing more.
  if (!exposureGiven && !o.scene.ev100.empty()) o.autoExposure.clear();
  // Its metering is checked as --metering is, naming the file.
  try {
    meteringRange(o);
  } catch (const Error&) {
    bad("metering", "must be [low, high] percentiles with 0 <= low < high <= 100");
  }
}

void runView(ViewCliOptions o, const GlobalOptions& global) {
  applySettingsFile(o);
  if (!o.screenshot.empty()) checkRenderedImagePath(o.screenshot);
  if (o.referenceSpp && o.reference.empty())
    failUsage("--reference-spp", "needs --reference reference, difference or split");
  if (!o.screenshot.empty() && given(o.scene, "--split") && o.reference != "split")
    failUsage("--split",
              "places the boundary of the split view; the screenshot needs --reference "
              "split");
  checkSceneOptions(o.scene);
  if (o.clay == "on" && !o.reference.empty())
    failUsage("--clay", fmt::format("draws the real-time frame as clay; --reference {} shows the "
                                    "shading compared with the reference",
                                    o.reference));
  if (o.buffer != "shaded" && !o.reference.empty())
    failUsage("--buffer", fmt::format("{} is a buffer of the real-time frame; --reference {} shows "
                                      "the shading compared with the reference",
                                      o.buffer, o.reference));
  if (!o.screenshot.empty() && o.buffer != "shaded")
    noteToneOptionsWithoutEffect(
        o.scene, fmt::format("--buffer {} shows its values as display colors", o.buffer), false,
        global);
  else if (!o.screenshot.empty() && viewMode(o.reference) == gpu::ViewMode::Difference)
    noteToneOptionsWithoutEffect(
        o.scene, "--reference difference shows the relative error in false colors", false, global);
  else if (!o.screenshot.empty() && fileFormatFromExtension(o.screenshot) == FileFormat::Exr)
    noteToneOptionsWithoutEffect(
        o.scene, fmt::format("{} holds linear radiance; write a .png", o.screenshot),
        bloomCompensation(o.scene, kViewBloom).has_value(), global);
  meteringRange(o);  // checked before the scene loads
  int accumulated = taaFrames(o);
  if (accumulated > 0 && o.buffer != "shaded" && !o.screenshot.empty()) {
    if (given(o.scene, "--taa"))
      failUsage("--taa", fmt::format("averages jittered frames of the shading; --buffer {} shows "
                                     "its values as they are",
                                     o.buffer));
    accumulated = 0;  // a settings file's: the window shows a buffer without temporal AA
  }
  if (o.autoExposure == "on" && fixedExposure(o.scene))
    failUsage("--auto-exposure",
              "on contradicts a fixed exposure (--ev100, or --aperture, --shutter and --iso)");
  if (!o.screenshot.empty() && o.frames > 0)
    failUsage("--frames", "closes the window after so many frames; --screenshot opens none");
  if (o.skyboxMip > 0.0f && (o.scene.background != "env" || environmentIsNone(o.scene)))
    failUsage("--skybox-mip",
              fmt::format("blurs the environment behind the scene; {} shows none",
                          environmentIsNone(o.scene) ? "--env none"
                                                     : "--background " + o.scene.background));
  const auto [width, height] = parseSize(o.scene.size);
  if (o.scene.aoRays > 0) failUsage("--ao", "ray-cast ambient occlusion is `ibl render`'s alone");
  if (o.scene.shadows == "ray")
    failUsage("--shadows", "ray is `ibl render`'s alone; the viewer casts shadow maps (map)");
  const std::vector<std::filesystem::path> inputs = sceneInputFiles(o.scene);
  if (!o.screenshot.empty()) {
    refuseOverwritingInputs({o.screenshot}, inputs);
    requireWritableFile(o.screenshot);
  }
  requireMemory(renderMemoryBytes(width, height), fmt::format("--size {}", o.scene.size),
                "view a smaller image");
  Scene scene = loadScene(o.scene, global);
  const Camera camera = frameCamera(o.scene, scene, width, height);  // checked before the bake
  const std::vector<LocalProbe> probes = loadProbes(o.scene.probes);
  checkVolumeUpdateFrames(o.scene);
  if (!o.volumeUpdate.empty() && o.scene.volume.empty())
    failUsage("--volume-update", "updates the volume of --volume, which is not given");
  if (o.volumeUpdate == "off" && o.scene.volumeUpdateFrames > 0)
    failUsage("--volume-update-frames", "contradicts --volume-update off");
  if (o.screenshot.empty() && o.scene.volumeUpdateFrames > 0)
    failUsage("--volume-update-frames",
              "runs before a --screenshot; the window updates the volume every frame");
  std::optional<IrradianceVolume> loadedVolume;
  if (!o.scene.volume.empty()) loadedVolume = loadVolume(o.scene.volume);
  const IrradianceVolume* volume = loadedVolume ? &*loadedVolume : nullptr;
  const std::vector<Light> ownLights = scene.lights;  // the scene's and --lights'
  const LoadedBake baked = loadOrBake(o.scene, global, hasSheen(scene));
  scene.lights.insert(scene.lights.end(), baked.lights.begin(), baked.lights.end());
  // A sky: its sun is always one light (0 lux below the horizon), so that the time of day can
  // replace it.
  const bool sky = isSkySpec(o.scene.env);
  std::optional<SkySpec> skySpec;
  if (sky) {
    skySpec = parseSkySpec(o.scene.env);
    if (baked.lights.empty()) {
      Light sun = skySun(skySpec->parameters);
      sun.intensity *= static_cast<float>(baked.envScale.factor);
      scene.lights.push_back(sun);
    }
  }
  RenderOptions shading = shadingOptions(o.scene, baked);
  shading.spp = o.scene.spp > 0 ? o.scene.spp : 4;
  shading.volume = volume;  // what the viewer composes (it reads the one it uploads)
  const auto warn = [&](const std::string& m) {
    if (!global.quiet) fmt::print(stderr, "ibl: warning: {}\n", m);
  };
  checkProbeShading(probes, shading, o.scene.force, warn);
  if (volume) checkCaptureShading(volume->capture, volume->path, shading, o.scene.force, warn);
  if (shading.realTimeShadows == ShadowMode::Map)
    requireMemory(shadowMapBytes(scene.lights, shading.shadowSettings, hasTransmission(scene)),
                  fmt::format("shadow maps of {} texels for {} lights", o.scene.shadowMapSize,
                              scene.lights.size()),
                  "use a smaller --shadow-map-size or --shadows none");

  const gpu::ViewMode view = viewMode(o.reference);
  const gpu::BufferView buffer = *gpu::bufferViewNamed(o.buffer);
  if (!o.screenshot.empty() && view != gpu::ViewMode::RealTime) {
    // The reference traced on the device, with the real-time frame it is compared with.
    gpu::ContextOptions co;
    co.graphics = true;
    const auto context = gpu::Context::create(co);
    gpu::PathTracer tracer(*context, scene, baked.bake, baked.options);
    tracer.reset(camera, gpu::viewReferenceOptions(shading));
    const int spp = o.referenceSpp.value_or(kScreenshotReferenceSpp);
    while (tracer.samplesPerPixel() < spp)
      tracer.accumulate(std::min(kScreenshotReferenceBatch, spp - tracer.samplesPerPixel()));
    const RenderResult reference = tracer.result();
    RenderResult realTime;
    if (view != gpu::ViewMode::Reference) {
      gpu::SceneRenderer renderer(*context, scene, baked.bake, baked.options, probes, volume,
                                  o.scene.volumeUpdateFrames > 0);
      updateVolumeBeforeScreenshot(renderer, camera, shading, o.scene, global);
      realTime = accumulated > 0
                     ? renderer.renderAccumulated(camera, shading, accumulated, o.skyboxMip)
                     : renderer.render(camera, shading, o.skyboxMip);
    }
    // Exposed for the reference, as the window's auto exposure meters it.
    const float ev100 = viewEv100(o, reference.color);
    writeView(o.screenshot, gpu::composeView(view, realTime, reference, o.split), view,
              gpu::BufferView::Shaded, ev100 - o.scene.compensation, toneCurve(o.scene), o.scene);
    if (!global.quiet)
      fmt::print(
          stderr,
          "screenshot {} ({}x{}, {}: {} samples per pixel, reference noise {:.2f} %, {:.1f} ms on "
          "{}, EV100 {:.2f})\n",
          o.screenshot, width, height, gpu::viewModeName(view), tracer.samplesPerPixel(),
          100.0f * tracer.noise(), reference.milliseconds, context->device().name, ev100);
    return;
  }
  if (!o.screenshot.empty()) {
    gpu::ContextOptions co;
    co.graphics = true;
    const auto context = gpu::Context::create(co);
    gpu::SceneRenderer renderer(*context, scene, baked.bake, baked.options, probes, volume,
                                o.scene.volumeUpdateFrames > 0);
    updateVolumeBeforeScreenshot(renderer, camera, shading, o.scene, global);
    renderer.setBufferView(buffer);
    renderer.setClay(o.clay == "on");
    // --taa N: N jittered frames averaged, what the window's temporal antialiasing converges to
    // while the camera stands still.
    RenderResult result =
        accumulated > 0 ? renderer.renderAccumulated(camera, shading, accumulated, o.skyboxMip)
                        : renderer.render(camera, shading, o.skyboxMip);
    if (renderer.samples() < shading.spp && !global.quiet)
      fmt::print(stderr, "ibl: warning: --spp {}: {} allows at most {}x MSAA; rendered with {}\n",
                 shading.spp, context->device().name, renderer.samples(), renderer.samples());
    const float ev100 =
        buffer == gpu::BufferView::Shaded ? viewEv100(o, result.color) : 0.0f;  // unexposed
    writeView(o.screenshot, result, gpu::ViewMode::RealTime, buffer, ev100 - o.scene.compensation,
              toneCurve(o.scene), o.scene);
    if (!global.quiet) {
      fmt::print(stderr, "screenshot {} ({}x{}, {}x MSAA{}, {:.1f} ms on {}, {})\n", o.screenshot,
                 width, height, renderer.samples(),
                 accumulated > 0 ? fmt::format(", {} jittered frames", accumulated) : "",
                 result.milliseconds, context->device().name,
                 buffer == gpu::BufferView::Shaded ? fmt::format("EV100 {:.2f}", ev100)
                                                   : fmt::format("buffer {}", o.buffer));
      // The passes' GPU time (timestamp queries), where the device writes them.
      std::string passes;
      for (const auto& [name, ms] : renderer.passTimes())
        passes += fmt::format("{}{} {:.1f} ms", passes.empty() ? "" : ", ", name, ms);
      if (!passes.empty())
        fmt::print(stderr, "passes: {}; device memory {:.1f} MB\n", passes,
                   static_cast<double>(context->deviceMemoryBytes()) / 1048576.0);
    }
    return;
  }
  gpu::WindowOptions w;
  w.camera = camera;
  w.render = shading;
  if (fixedExposure(o.scene)) w.ev100 = chooseEv100(o.scene, Image(1, 1));
  if (o.scene.ev100.empty() && fixedExposure(o.scene)) {
    w.aperture = o.scene.aperture;
    w.shutter = o.scene.shutter;
    w.iso = o.scene.iso;
  }
  w.autoExposure = o.autoExposure != "off";
  w.metering = meteringRange(o);
  w.adaptationSpeed = o.adaptationSpeed;
  w.panel = o.panel == "on";
  w.compensation = o.scene.compensation;
  w.toneMap = toneCurve(o.scene);
  w.skyboxLod = o.skyboxMip;
  w.bloom = bloomCompensation(o.scene, kViewBloom);
  w.frames = o.frames;
  w.title = "ibl view " + o.scene.scene;
  w.view = view;
  w.buffer = buffer;
  w.clay = o.clay == "on";
  w.temporalAntialiasing = o.taa != "off";
  w.split = o.split;
  w.referenceSpp = o.referenceSpp.value_or(0);
  w.volumeUpdate = o.volumeUpdate != "off";
  w.screenshot = [&](const RenderResult& result, float ev100, ToneMap curve, gpu::ViewMode shown,
                     gpu::BufferView shownBuffer) {
    const std::string path = unusedName("ibl_view", ".png");
    writeView(path, result, shown, shownBuffer, ev100, curve, o.scene);
    if (!global.quiet) fmt::print(stderr, "screenshot {}\n", path);
  };
  w.saveSettings = [](const gpu::ViewSettings& settings) {
    const std::string path = unusedName("ibl_view_settings", ".json");
    const std::string text = settingsJson(settings);
    writeFileAtomic(path, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
    return path;
  };
  w.saveLights = [](const std::vector<Light>& lights) {
    const std::string path = unusedName("ibl_view_lights", ".json");
    const std::string text = lightsFileText(lights);
    writeFileAtomic(path, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
    return path;
  };
  if (skySpec) {
    // , and . move the sun 5 degrees; the sky is recomputed and baked on the viewer's device.
    w.timeOfDay = [&, parameters = skySpec->parameters](
                      int step,
                      gpu::Context& device) mutable -> std::optional<gpu::EnvironmentChange> {
      const float elevation =
          std::clamp(parameters.sunElevation + 5.0f * static_cast<float>(step), -10.0f, 90.0f);
      if (elevation == parameters.sunElevation) return std::nullopt;
      parameters.sunElevation = elevation;
      gpu::EnvironmentChange change;
      // The sky and its bake on the viewer's GPU; on the CPU when that is the software
      // rasterizer (lavapipe takes seconds where the CPU paths take under one).
      gpu::Context* const hardware = gpu::isHardwareDevice(device.device()) ? &device : nullptr;
      Environment env;
      env.equirect =
          gpu::skyPanoramaOn(hardware, parameters, skySpec->width, skySpec->height, false);
      // --env-intensity / --env-illuminance: the factor found for the first sky, kept.
      Light sun = skySun(parameters);
      if (baked.envScale.factor != 1.0) {
        scaleEnvironment(env, baked.envScale.factor, o.scene.env);
        sun.intensity *= static_cast<float>(baked.envScale.factor);
      }
      change.options = baked.options;
      change.bake = bakeEnvironment(env, change.options, {}, hardware);
      change.lights = ownLights;
      change.lights.push_back(sun);
      change.label = fmt::format("sun at {:.0f} degrees, {:.0f} lx, baked on {}", elevation,
                                 change.lights.back().intensity,
                                 hardware ? device.device().name : std::string("the CPU"));
      return change;
    };
  }
  // A dropped environment is loaded (or, a folder, read as a bake) as --env (--bake) would be,
  // scaled as --env-intensity / --env-illuminance asked, and baked on the CPU. Its sun takes the
  // place of the scene's environment sun; without one there, that light goes dark; a sun the
  // scene has no place for is left out (said on stderr).
  const std::size_t ownCount = ownLights.size();
  w.dropEnvironment = [&](const std::string& path,
                          gpu::Context&) -> std::optional<gpu::EnvironmentChange> {
    SceneCliOptions dropped = o.scene;
    dropped.envPixels.reset();
    if (std::filesystem::is_directory(path)) {
      dropped.bakeDir = path;
      dropped.env.clear();
    } else {
      dropped.env = path;
      dropped.bakeDir.clear();
    }
    GlobalOptions quiet = global;
    quiet.quiet = true;
    LoadedBake lighting = loadOrBake(dropped, quiet, hasSheen(scene));
    gpu::EnvironmentChange change;
    change.bake = std::move(lighting.bake);
    change.options = lighting.options;
    change.lights = ownLights;
    for (std::size_t i = ownCount; i < scene.lights.size(); ++i) {
      const std::size_t k = i - ownCount;
      Light sun = k < lighting.lights.size() ? lighting.lights[k] : scene.lights[i];
      if (k >= lighting.lights.size()) sun.intensity = 0.0f;
      change.lights.push_back(sun);
    }
    if (lighting.lights.size() > scene.lights.size() - ownCount && !global.quiet)
      fmt::print(stderr,
                 "ibl view: {}: its sun is left out (the scene had no sun light to carry it; "
                 "start with --env {} to see it)\n",
                 path, path);
    change.label = std::filesystem::path(path).filename().string();
    return change;
  };
  const gpu::WindowStats stats =
      gpu::runViewerWindow(scene, baked.bake, baked.options, w, probes, volume);
  if (!global.quiet) {
    if (stats.samples < shading.spp)
      fmt::print(stderr, "ibl: warning: --spp {}: {} allows at most {}x MSAA; rendered with {}\n",
                 shading.spp, stats.device, stats.samples, stats.samples);
    fmt::print(stderr, "viewed {} frames, {:.2f} ms per frame on {}, EV100 {:.2f} at the end\n",
               stats.frames, stats.meanFrameMs, stats.device, stats.ev100);
    if (stats.referenceSpp > 0)
      fmt::print(
          stderr,
          "reference at {} samples per pixel, reference noise {:.2f} % ({} view at the end)\n",
          stats.referenceSpp, 100.0f * stats.referenceNoise, gpu::viewModeName(stats.view));
  }
}

}  // namespace

void addViewCommand(CLI::App& app, const GlobalOptions& global) {
  auto opts = std::make_shared<ViewCliOptions>();
  opts->scene.size = "1280x720";
  CLI::App* cmd = app.add_subcommand(
      "view", "Real-time viewer (Vulkan): a window, or a headless screenshot with --screenshot");
  addSceneOptions(cmd, opts->scene);
  addVolumeOption(cmd, opts->scene);
  cmd->add_option("--volume-update", opts->volumeUpdate,
                  "Window: on (default) runs a frame of the volume's live update before every "
                  "frame (rays traced on the device), so that the sun, the sky and the lights "
                  "relight it; off keeps the volume as baked")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--screenshot", opts->screenshot,
                  "Render offscreen to this image (.png or .exr) and exit, without a window; "
                  "missing folders are created");
  cmd->add_option("--spp", opts->scene.spp, "Multisamples per pixel: 1, 2, 4 or 8 (default 4)")
      ->check(CLI::IsMember({1, 2, 4, 8}));
  cmd->add_option("--skybox-mip", opts->skyboxMip, "Mip level of the skybox (0: sharpest)")
      ->check(numberIn(0.0f, 16.0f))
      ->capture_default_str();
  cmd->add_option("--auto-exposure", opts->autoExposure,
                  "Window: on (default without --ev100 or camera settings) meters every frame "
                  "and eases the exposure toward it; off keeps the first frame's")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--metering", opts->metering,
                  "Auto exposure meters the pixels between these percentiles of luminance, "
                  "LOW,HIGH (the darkest and brightest left out; screenshots too)")
      ->capture_default_str();
  cmd->add_option("--adaptation-speed", opts->adaptationSpeed,
                  "Window: how fast auto exposure follows the light, per second (the gap "
                  "shrinks by e^-speed each second; 0: at once)")
      ->check(numberIn(0.0f, 1000.0f))
      ->capture_default_str();
  std::vector<std::string> buffers;
  for (int i = 0; i < gpu::kBufferViewCount; ++i)
    buffers.emplace_back(gpu::bufferViewName(static_cast<gpu::BufferView>(i)));
  cmd->add_option("--buffer", opts->buffer,
                  "Show one input of the real-time frame instead of its shading, as display "
                  "colors (no exposure, bloom or tone curve): the material's base-color, "
                  "roughness (specular antialiasing included), metallic, world normals, "
                  "occlusion texture; gtao; the sun's shadow cascades; lights per cluster "
                  "(clusters); screen-space reflection hits (reflections); probe and volume "
                  "influence; validation, which marks implausible materials (V cycles them)")
      ->check(CLI::IsMember(buffers))
      ->capture_default_str();
  cmd->add_option("--clay", opts->clay,
                  "Draw every material as one matte gray dielectric (base color 0.5, roughness "
                  "0.6), normal maps and occlusion kept, to judge shapes and light alone (C "
                  "toggles it)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--taa", opts->taa,
                  "Temporal antialiasing: the window's frames jittered and blended into a "
                  "reprojected, clipped history (on by default there; off turns it off); a "
                  "screenshot averages N jittered frames (on: 16; default: one unjittered frame)");
  cmd->add_option("--panel", opts->panel,
                  "Window: show the panel of settings, lights and figures at the start (F1 "
                  "toggles it; screenshots never show it)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--settings", opts->settings,
                  "Show what a settings file saved by the panel describes (camera, exposure, "
                  "tone curve, bloom, terms, view); options given here win over the file's");
  cmd->add_option("--frames", opts->frames, "Window: close after this many frames (0: never)")
      ->check(numberIn(0, 1 << 30));
  cmd->add_option("--reference", opts->reference,
                  "Show the path-traced reference (on the device): reference, difference (the "
                  "real-time frame's relative error, as `ibl compare --error-png`) or split "
                  "(left real time, right reference); the screenshot's picture, or the window's "
                  "first view (M cycles)")
      ->check(CLI::IsMember({"reference", "difference", "split"}));
  cmd->add_option("--split", opts->split,
                  "The split view's boundary, as a share of the width from the left (the real-time "
                  "frame left of it, the reference right)")
      ->check(numberIn(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--reference-spp", opts->referenceSpp,
                  "With --reference: the reference's samples per pixel (screenshot: default 64; "
                  "window: where it stops adding samples)")
      ->check(numberIn(1, 1 << 20));
  cmd->footer(
      "Window controls (the panel, F1, has every setting):\n"
      "  F1             show / hide the panel\n"
      "  A              auto exposure on / off     B   bloom on / off\n"
      "  left drag      orbit around the target      wheel   zoom\n"
      "  + / -          exposure up / down (half stops)\n"
      "  [ / ]          skybox mip level down / up\n"
      "  D / S          toggle the diffuse / specular term\n"
      "  T              cycle the tone curve (ACES, filmic, none)\n"
      "  M              cycle the view: real time, reference (path traced on the device,\n"
      "                 refined while the view stands still), difference, split\n"
      "  P or F12       screenshot of the current view to ibl_view_NNN.png (working directory)\n"
      "  , / .          with --env sky:...: the sun 5 degrees lower / higher (the sky\n"
      "                 recomputed, and baked on the viewer's GPU)\n"
      "  R              reset the camera      Esc / Q   quit");
  cmd->callback([opts, &global] { runView(*opts, global); });
}

}  // namespace ibl::cli
