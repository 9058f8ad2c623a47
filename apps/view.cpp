// `ibl view`: the real-time viewer (Vulkan), in a window or headless to a screenshot.
#include <string>

#include <fmt/core.h>

#include "commands.hpp"
#include "ibl/gpu/viewer.hpp"
#include "scene_options.hpp"

namespace ibl::cli {

namespace {

struct ViewCliOptions {
  SceneCliOptions scene;
  std::string screenshot;
  int frames = 0;
  float skyboxMip = 0.0f;
};

void runView(const ViewCliOptions& o, const GlobalOptions& global) {
  if (!o.screenshot.empty()) checkRenderedImagePath(o.screenshot);
  const auto [width, height] = parseSize(o.scene.size);
  const Scene scene = loadScene(o.scene);
  const Camera camera = frameCamera(o.scene, scene, width, height);  // checked before the bake
  const LoadedBake baked = loadOrBake(o.scene);
  RenderOptions shading = shadingOptions(o.scene);
  shading.spp = o.scene.spp > 0 ? o.scene.spp : 4;

  if (!o.screenshot.empty()) {
    gpu::ContextOptions co;
    co.graphics = true;
    const auto context = gpu::Context::create(co);
    gpu::SceneRenderer renderer(*context, scene, baked.bake, baked.options);
    const RenderResult result = renderer.render(camera, shading, o.skyboxMip);
    const float ev100 = chooseEv100(o.scene, result.color);
    writeRenderedImage(o.screenshot, result, ev100 - o.scene.compensation, toneCurve(o.scene),
                       false);
    if (!global.quiet)
      fmt::print(stderr, "screenshot {} ({}x{}, {}x MSAA, {:.1f} ms on {}, EV100 {:.2f})\n",
                 o.screenshot, width, height, renderer.samples(), result.milliseconds,
                 context->device().name, ev100);
    return;
  }
  gpu::WindowOptions w;
  w.camera = camera;
  w.render = shading;
  if (!o.scene.ev100.empty() || (o.scene.aperture > 0 && o.scene.shutter > 0 && o.scene.iso > 0))
    w.ev100 = chooseEv100(o.scene, Image(1, 1));
  w.compensation = o.scene.compensation;
  w.toneMap = toneCurve(o.scene);
  w.skyboxLod = o.skyboxMip;
  w.frames = o.frames;
  w.title = "ibl view " + o.scene.scene;
  const gpu::WindowStats stats = gpu::runViewerWindow(scene, baked.bake, baked.options, w);
  if (!global.quiet)
    fmt::print(stderr, "viewed {} frames, {:.2f} ms per frame on {}\n", stats.frames,
               stats.meanFrameMs, stats.device);
}

}  // namespace

void addViewCommand(CLI::App& app, const GlobalOptions& global) {
  auto opts = std::make_shared<ViewCliOptions>();
  opts->scene.size = "1280x720";
  CLI::App* cmd = app.add_subcommand(
      "view", "Real-time viewer (Vulkan): a window, or a headless screenshot with --screenshot");
  addSceneOptions(cmd, opts->scene);
  cmd->add_option("--screenshot", opts->screenshot,
                  "Render offscreen to this image (.png or .exr) and exit, without a window");
  cmd->add_option("--spp", opts->scene.spp, "Multisamples per pixel (default 4)")
      ->check(CLI::Range(1, 64));
  cmd->add_option("--skybox-mip", opts->skyboxMip, "Mip level of the skybox (0: sharpest)")
      ->check(CLI::Range(0.0f, 16.0f))
      ->capture_default_str();
  cmd->add_option("--frames", opts->frames, "Window: close after this many frames (0: never)")
      ->check(CLI::Range(0, 1 << 30));
  cmd->callback([opts, &global] { runView(*opts, global); });
}

}  // namespace ibl::cli
