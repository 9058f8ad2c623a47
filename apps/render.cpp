// `ibl render`: a glTF model or a built-in scene, lit by a baked environment.
#include <cstdio>
#include <sstream>
#include <string>

#include <fmt/core.h>
#include <unistd.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "commands.hpp"
#include "ibl/bake.hpp"
#include "ibl/camera.hpp"
#include "ibl/color.hpp"
#include "ibl/default_environment.hpp"
#include "ibl/error.hpp"
#include "ibl/file_io.hpp"
#include "ibl/image_io.hpp"
#include "ibl/render.hpp"

namespace ibl::cli {

namespace {

struct RenderCliOptions {
  std::string scene;
  std::string env;  // empty: bundled default
  std::string bakeDir;
  std::string output;
  std::string mode = "split-sum";
  std::string camera = "perspective";
  float fov = 40.0f;
  float orthoWidth = 0.0f;
  std::string lookFrom, lookAt, up = "0,1,0";
  std::string size = "512x512";
  int spp = 0;  // 0: 4 (split sum) or 256 (reference)
  float noise = 0.0f;
  std::string baseColor = "1,1,1";
  float metallic = 0.0f;
  float roughness = 0.5f;
  std::string diffuse = "disney";
  std::string only;
  bool noMultiscatter = false;
  bool noDominant = false;
  std::string irradiance = "cube";
  bool shadows = false;
  std::string background = "env";
  std::string ev100;  // empty: automatic
  float aperture = 0.0f, shutter = 0.0f, iso = 0.0f;
  float compensation = 0.0f;
  std::string tonemap = "aces";
  bool exrExposed = false;
  unsigned seed = 1;
};

glm::vec3 parseVec3(const std::string& text, const char* option) {
  glm::vec3 v;
  char c1, c2;
  std::istringstream in(text);
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !in.eof())
    fail(option, fmt::format("expected X,Y,Z, got '{}'", text));
  return v;
}

void runRender(const RenderCliOptions& o, const GlobalOptions& global) {
  const auto format = fileFormatFromExtension(o.output);
  if (format != FileFormat::Exr && format != FileFormat::Png)
    fail(o.output, "output must be .exr or .png");
  int width = 0, height = 0;
  {
    char x = 0;
    std::istringstream in(o.size);
    if (!(in >> width >> x >> height) || x != 'x' || width < 1 || height < 1 || width > 16384 ||
        height > 16384)
      fail("--size", fmt::format("expected WxH (1 to 16384), got '{}'", o.size));
  }
  // The scene.
  Scene scene;
  if (o.scene == "sphere" || o.scene == "grid") {
    const glm::vec3 base = parseVec3(o.baseColor, "--base-color");
    if (o.scene == "sphere") {
      Material m;
      m.baseColor = base;
      m.metallic = o.metallic;
      m.roughness = o.roughness;
      scene = makeSphereScene(m);
    } else {
      scene = makeSphereGrid(base);
    }
  } else {
    scene = loadGltf(o.scene);
  }
  // The environment: an existing bake, or bake now.
  BakeOptions bakeOptions;
  BakeResult bake;
  if (!o.bakeDir.empty()) {
    bake = loadBake(o.bakeDir, &bakeOptions);
  } else {
    const LoadedEnvironment env =
        o.env.empty()
            ? loadEnvironmentFromMemory(defaultEnvironmentBytes(), kDefaultEnvironmentName)
            : loadEnvironment(o.env);
    bakeOptions.dfgSamples = 256;
    bake = bakeEnvironment(env.environment, bakeOptions);
  }
  // The camera: options, else the file's, else framing the scene from +Z.
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.perspective = o.camera == "perspective";
  camera.yfovDegrees = o.fov;
  const auto [lo, hi] = scene.bounds();
  const glm::vec3 center = 0.5f * (lo + hi);
  const float radius = 0.5f * glm::length(hi - lo);
  if (scene.camera && o.lookFrom.empty() && o.lookAt.empty()) {
    const CameraDescription& d = *scene.camera;
    camera.perspective = d.perspective;
    camera.yfovDegrees = glm::degrees(d.yfovRadians);
    camera.orthoWidth = 2.0f * d.xmag;
    camera.from = glm::vec3(d.world[3]);
    camera.at = camera.from - glm::vec3(d.world[2]);
    camera.up = glm::vec3(d.world[1]);
  } else {
    camera.at = o.lookAt.empty() ? center : parseVec3(o.lookAt, "--look-at");
    // Frame the bounds seen from +Z: fit their width and height, then back off by their depth.
    const glm::vec3 half = 0.5f * (hi - lo);
    const float t = std::tan(0.5f * glm::radians(camera.yfovDegrees));
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const float distance = 1.1f * std::max(half.y / t, half.x / (t * aspect)) + half.z;
    camera.from = o.lookFrom.empty() ? camera.at + glm::vec3(0.0f, 0.0f, distance)
                                     : parseVec3(o.lookFrom, "--look-from");
    camera.up = parseVec3(o.up, "--up");
    camera.orthoWidth = o.orthoWidth > 0.0f
                            ? o.orthoWidth
                            : 2.2f * radius * std::max(1.0f, float(width) / float(height));
  }
  if (o.orthoWidth > 0.0f) camera.orthoWidth = o.orthoWidth;

  RenderOptions r;
  r.mode = o.mode == "reference" ? RenderMode::Reference : RenderMode::SplitSum;
  r.diffuse = o.diffuse == "lambert" ? DiffuseModel::Lambert : DiffuseModel::Disney;
  r.only = o.only == "diffuse"    ? ShadingTerms::Diffuse
           : o.only == "specular" ? ShadingTerms::Specular
                                  : ShadingTerms::Both;
  r.spp = o.spp > 0 ? o.spp : (r.mode == RenderMode::Reference ? 256 : 4);
  r.noiseThreshold = o.noise;
  r.multipleScattering = !o.noMultiscatter;
  r.dominantDirections = !o.noDominant;
  r.irradiance = o.irradiance == "sh" ? IrradianceSource::Sh : IrradianceSource::Cube;
  r.shadows = o.shadows;
  r.seed = o.seed;
  if (o.background != "env") {
    r.backgroundEnvironment = false;
    r.backgroundColor = parseVec3(o.background, "--background");
  }
  const bool showProgress = !global.quiet && ::isatty(STDERR_FILENO);
  const RenderResult result = renderScene(scene, camera, bake, bakeOptions, r, [&](float f) {
    if (showProgress) fmt::print(stderr, "\rrendering {:3.0f} %", 100.0f * f);
  });
  if (showProgress) fmt::print(stderr, "\r");

  // Exposure: settings, EV100, or automatic from the image.
  float ev100;
  if (!o.ev100.empty()) {
    ev100 = std::stof(o.ev100);
  } else if (o.aperture > 0.0f && o.shutter > 0.0f && o.iso > 0.0f) {
    ev100 = ev100FromSettings(o.aperture, o.shutter, o.iso);
  } else {
    ev100 = ev100FromAverageLuminance(averageLogLuminance(result.color));
  }
  const float exposure = exposureFromEv100(ev100 - o.compensation);
  const ToneMap curve = o.tonemap == "none"     ? ToneMap::None
                        : o.tonemap == "filmic" ? ToneMap::Filmic
                                                : ToneMap::Aces;
  Image exposed(result.color.width, result.color.height);
  for (std::size_t i = 0; i < exposed.pixels.size(); ++i)
    exposed.pixels[i] = toneMap(result.color.pixels[i] * exposure, curve);

  if (format == FileFormat::Exr) {
    writeFileAtomic(o.output, encodeExr(o.exrExposed ? exposed : result.color, ExrPixelType::Float,
                                        &result.alpha));
  } else {
    writeFileAtomic(o.output, encodePng(exposed));
  }
  if (!global.quiet)
    fmt::print(
        stderr,
        "rendered {} ({}x{}, {}, {:.0f} samples, {:.2f} s, {:.2f} M samples/s, EV100 {:.2f})\n",
        o.output, width, height, o.mode, result.samples, result.milliseconds / 1000.0,
        result.samples / result.milliseconds / 1000.0, ev100);
}

}  // namespace

void addRenderCommand(CLI::App& app, const GlobalOptions& global) {
  auto opts = std::make_shared<RenderCliOptions>();
  CLI::App* cmd =
      app.add_subcommand("render", "Render a glTF model or a built-in scene lit by an environment");
  cmd->add_option("scene", opts->scene, "glTF file (.gltf, .glb), 'sphere' or 'grid'")->required();
  cmd->add_option("--env", opts->env,
                  "Environment to bake and light with (default: the bundled sunset.exr)");
  cmd->add_option("--bake", opts->bakeDir,
                  "Use an existing bake directory instead of baking --env");
  cmd->add_option("-o,--output", opts->output,
                  "Output image: .exr (linear radiance + alpha) or .png")
      ->required();
  cmd->add_option("--mode", opts->mode, "split-sum (real time) or reference (Monte Carlo)")
      ->check(CLI::IsMember({"split-sum", "reference"}))
      ->capture_default_str();
  cmd->add_option("--camera", opts->camera, "perspective or ortho")
      ->check(CLI::IsMember({"perspective", "ortho"}))
      ->capture_default_str();
  cmd->add_option("--fov", opts->fov, "Vertical field of view in degrees")
      ->check(CLI::Range(1.0f, 179.0f))
      ->capture_default_str();
  cmd->add_option("--ortho-width", opts->orthoWidth,
                  "Width of the orthographic view (default: fits the scene)");
  cmd->add_option("--look-from", opts->lookFrom,
                  "Camera position X,Y,Z (default: in front of the scene, +Z)");
  cmd->add_option("--look-at", opts->lookAt, "Point looked at X,Y,Z (default: the scene's center)");
  cmd->add_option("--up", opts->up, "Up vector X,Y,Z")->capture_default_str();
  cmd->add_option("--size", opts->size, "Image size WxH")->capture_default_str();
  cmd->add_option("--spp", opts->spp, "Samples per pixel (default 4 split-sum, 256 reference)")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--noise", opts->noise, "Reference: stop a pixel at this relative standard error")
      ->check(CLI::Range(0.0f, 1.0f));
  cmd->add_option("--base-color", opts->baseColor, "Built-in scenes: linear base color R,G,B")
      ->capture_default_str();
  cmd->add_option("--metallic", opts->metallic, "Built-in sphere: metallic")
      ->check(CLI::Range(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--roughness", opts->roughness, "Built-in sphere: perceptual roughness")
      ->check(CLI::Range(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--diffuse", opts->diffuse, "disney (Frostbite renormalized) or lambert")
      ->check(CLI::IsMember({"disney", "lambert"}))
      ->capture_default_str();
  cmd->add_option("--only", opts->only, "Isolate a term: diffuse or specular")
      ->check(CLI::IsMember({"diffuse", "specular"}));
  cmd->add_flag("--no-multiscatter", opts->noMultiscatter,
                "Split sum: no multiple-scattering compensation");
  cmd->add_flag("--no-dominant", opts->noDominant,
                "Split sum: sample along n and r, not the dominant directions");
  cmd->add_option("--irradiance", opts->irradiance,
                  "Split sum: diffuse from the irradiance cube or SH9")
      ->check(CLI::IsMember({"cube", "sh"}))
      ->capture_default_str();
  cmd->add_flag("--shadows", opts->shadows, "Reference: ray-traced visibility of the environment");
  cmd->add_option("--background", opts->background, "'env' (the environment) or a color R,G,B")
      ->capture_default_str();
  cmd->add_option("--ev100", opts->ev100,
                  "Exposure value at ISO 100 (default: automatic, average log luminance)");
  cmd->add_option("--aperture", opts->aperture, "f-number (with --shutter and --iso)");
  cmd->add_option("--shutter", opts->shutter, "Shutter time in seconds");
  cmd->add_option("--iso", opts->iso, "Sensitivity");
  cmd->add_option("--exposure-compensation", opts->compensation, "Stops added to the exposure")
      ->capture_default_str();
  cmd->add_option("--tonemap", opts->tonemap, "none, aces or filmic")
      ->check(CLI::IsMember({"none", "aces", "filmic"}))
      ->capture_default_str();
  cmd->add_flag("--exr-exposed", opts->exrExposed,
                "Write the exposed, tone-mapped image to the EXR too");
  cmd->add_option("--seed", opts->seed, "Random seed of the reference")->capture_default_str();
  cmd->callback([opts, &global] { runRender(*opts, global); });
}

}  // namespace ibl::cli
