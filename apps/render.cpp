// `ibl render`: a glTF model or a built-in scene, lit by a baked environment.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <unistd.h>

#include "commands.hpp"
#include "ibl/core/error.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/gpu/path_tracer.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/render/bloom.hpp"
#include "ibl/render/irradiance_volume.hpp"
#include "ibl/render/probe.hpp"
#include "preflight.hpp"
#include "render.hpp"
#include "scene_options.hpp"

namespace ibl::cli {

namespace {

void runRender(const RenderCliOptions& o, const GlobalOptions& global) {
  const auto start = std::chrono::steady_clock::now();  // the whole command's wall time
  // (An empty --output is Python's image kept in memory, not the command's.)
  if (o.output.empty()) failUsage("--output", "is empty: name the image to write");
  const bool showProgress = !global.quiet && ::isatty(STDERR_FILENO);
  const auto report = [&](float f) {
    if (showProgress) fmt::print(stderr, "\rrendering {:3.0f} %", 100.0f * f);
  };
  const RenderedImage image = renderImage(o, global, report);
  if (showProgress) fmt::print(stderr, "\r");
  writeRenderOutput(o, image);
  const RenderResult& result = image.result;
  // The wall time of it all (loading, baking, shadow maps, occlusion, shading, writing); the
  // shading's own rate beside it.
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!global.quiet)
    fmt::print(
        stderr,
        "rendered {} ({}x{}, {}, {:.0f} samples, {:.2f} s in all, {:.2f} s shading, {:.2f} M "
        "samples/s, EV100 {:.2f})\n",
        o.output, result.color.width, result.color.height, o.mode, result.samples, seconds,
        result.milliseconds / 1000.0, result.samples / result.milliseconds / 1000.0, image.ev100);
}

}  // namespace

RenderedImage renderImage(const RenderCliOptions& o, const GlobalOptions& global,
                          const std::function<void(float)>& report) {
  if (!o.output.empty()) checkRenderedImagePath(o.output);
  if (o.mode == "reference" && o.scene.shadows == "map")
    failUsage("--shadows", "map is the split sum's; the reference traces rays (--shadows ray)");
  if (o.device == "gpu" && o.mode != "reference")
    failUsage("--device",
              "gpu runs the reference: add --mode reference (the split sum on the GPU "
              "is `ibl view`)");
  if (o.device == "gpu" && o.noise > 0.0f)
    failUsage("--noise", "adaptive stopping is the CPU reference's; use --device cpu");
  // The mode's options first: what the other mode alone reads is the first mistake to name.
  refuseOptionsTheModeIgnores(o.scene, o.mode == "reference",
                              o.scene.spp > 0 ? o.scene.spp : (o.mode == "reference" ? 256 : 4),
                              o.bounces, o.noise);
  checkSceneOptions(o.scene);
  if (!o.output.empty()) {
    const bool exr = fileFormatFromExtension(o.output) == FileFormat::Exr;
    if (o.exrExposed && !exr && !global.quiet)
      fmt::print(stderr, "ibl: note: --exr-exposed: no effect: {} is exposed and tone-mapped\n",
                 o.output);
    if (exr && !o.exrExposed)
      noteToneOptionsWithoutEffect(
          o.scene,
          fmt::format("{} holds linear radiance; add --exr-exposed or write a .png", o.output),
          bloomCompensation(o.scene, std::nullopt).has_value(), global);
  }
  const auto [width, height] = parseSize(o.scene.size);
  const std::vector<std::filesystem::path> inputs = sceneInputFiles(o.scene);
  if (!o.output.empty()) {
    refuseOverwritingInputs({o.output}, inputs);
    requireWritableFile(o.output);
  }
  requireMemory(renderMemoryBytes(width, height), fmt::format("--size {}", o.scene.size),
                "render a smaller image");
  Scene scene = loadScene(o.scene, global);
  const Camera camera = frameCamera(o.scene, scene, width, height);  // checked before the bake
  const std::vector<LocalProbe> probes = loadProbes(o.scene.probes);
  checkVolumeUpdateFrames(o.scene);
  std::optional<IrradianceVolume> volume =
      o.scene.volume.empty() ? std::nullopt : std::optional(loadVolume(o.scene.volume));
  const LoadedBake baked = loadOrBake(o.scene, global, hasSheen(scene));
  scene.lights.insert(scene.lights.end(), baked.lights.begin(), baked.lights.end());
  RenderOptions r = shadingOptions(o.scene, baked);
  if (o.mode != "reference" && r.realTimeShadows == ShadowMode::Map)
    requireMemory(shadowMapBytes(scene.lights, r.shadowSettings, hasTransmission(scene)),
                  fmt::format("shadow maps of {} texels for {} lights", o.scene.shadowMapSize,
                              scene.lights.size()),
                  "use a smaller --shadow-map-size or --shadows none");
  r.mode = o.mode == "reference" ? RenderMode::Reference : RenderMode::SplitSum;
  r.spp = o.scene.spp > 0 ? o.scene.spp : (r.mode == RenderMode::Reference ? 256 : 4);
  r.noiseThreshold = o.noise;
  // --shadows ray: the reference's visibility (the split sum's mode is realTimeShadows).
  r.shadows = o.scene.shadows == "ray";
  r.bounces = o.bounces;
  // The reference reads no probe: only the split sum must match their shading.
  if (o.mode != "reference") {
    const auto warn = [&](const std::string& m) {
      if (!global.quiet) fmt::print(stderr, "ibl: warning: {}\n", m);
    };
    checkProbeShading(probes, r, o.scene.force, warn);
    if (volume) checkCaptureShading(volume->capture, volume->path, r, o.scene.force, warn);
  }
  r.probes = &probes;
  if (volume && o.scene.volumeUpdateFrames > 0) {
    // The live update the viewer would run, frame after frame, from the baked volume
    // (docs/probes.md, "The live update").
    const auto start = std::chrono::steady_clock::now();
    for (int frame = 0; frame < o.scene.volumeUpdateFrames; ++frame)
      updateVolume(scene, *volume, baked.bake, baked.options, r, VolumeUpdateOptions{},
                   static_cast<unsigned>(frame));
    if (!global.quiet)
      fmt::print(stderr, "volume updated over {} frames in {:.2f} s\n", o.scene.volumeUpdateFrames,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  r.volume = volume ? &*volume : nullptr;
  r.seed = o.seed;
  // auto picks a real GPU for the reference only, and not for --noise (the CPU's).
  const std::unique_ptr<gpu::Context> device =
      o.mode == "reference" && !(o.device == "auto" && o.noise > 0.0f)
          ? gpu::openComputeDevice(deviceChoice(o.device))
          : nullptr;
  if (device && !global.quiet) fmt::print(stderr, "reference on {}\n", device->device().name);
  RenderResult result =
      device ? gpu::renderReference(*device, scene, camera, baked.bake, baked.options, r, report)
             : renderScene(scene, camera, baked.bake, baked.options, r, report);
  const float ev100 = chooseEv100(o.scene, result.color);
  if (const std::optional<float> bloom = bloomCompensation(o.scene, std::nullopt))
    result.color = applyBloom(result.color, ev100 - o.scene.compensation, *bloom);
  return {std::move(result), ev100};
}

void writeRenderOutput(const RenderCliOptions& o, const RenderedImage& image) {
  writeRenderedImage(o.output, image.result, image.ev100 - o.scene.compensation, toneCurve(o.scene),
                     o.exrExposed);
}

void addRenderCommand(CLI::App& app, const GlobalOptions& global) {
  auto opts = std::make_shared<RenderCliOptions>();
  CLI::App* cmd = addRenderOptions(app, *opts);
  cmd->callback([opts, &global] { runRender(*opts, global); });
}

CLI::App* addRenderOptions(CLI::App& app, RenderCliOptions& o) {
  RenderCliOptions* opts = &o;
  CLI::App* cmd =
      app.add_subcommand("render", "Render a glTF model or a built-in scene lit by an environment");
  addSceneOptions(cmd, opts->scene);
  addVolumeOption(cmd, opts->scene);
  cmd->add_option("-o,--output", opts->output,
                  "Output image: .exr (linear radiance + alpha) or .png; missing folders are "
                  "created")
      ->required();
  cmd->add_option("--mode", opts->mode, "split-sum (real time) or reference (Monte Carlo)")
      ->check(CLI::IsMember({"split-sum", "reference"}))
      ->capture_default_str();
  cmd->add_option("--spp", opts->scene.spp,
                  "Samples per pixel (default 4 split-sum, 256 reference)")
      ->check(numberIn(1, 1 << 20));
  cmd->add_option("--noise", opts->noise, "Reference: stop a pixel at this relative standard error")
      ->check(numberIn(0.0f, 1.0f));
  cmd->add_option("--bounces", opts->bounces,
                  "Reference: bounces of indirect light between surfaces (path tracing, with "
                  "shadows); 0: direct light only")
      ->check(numberIn(0, 1000))
      ->capture_default_str();
  cmd->add_option("--shadow-rays", opts->scene.shadowRays,
                  "Split sum with --shadows ray: rays per area light or sun and pixel sample")
      ->check(numberIn(1, 4096))
      ->capture_default_str();
  cmd->add_flag("--exr-exposed", opts->exrExposed,
                "Write the exposed, tone-mapped image to the EXR too");
  cmd->add_option("--seed", opts->seed,
                  "Random seed of the sample sequences (the reference's paths; the split sum's "
                  "positions in the pixel and its rays)")
      ->capture_default_str();
  cmd->add_option("--device", opts->device,
                  "Reference: cpu, gpu (a Vulkan compute path tracer: the same paths and "
                  "numbers), or auto (a real GPU if present)")
      ->check(CLI::IsMember({"cpu", "gpu", "auto"}))
      ->capture_default_str();
  return cmd;
}

}  // namespace ibl::cli
