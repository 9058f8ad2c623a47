#pragma once
// The real-time viewer on Vulkan: the scene rasterized and shaded with the split sum of
// `ibl render` (the formulas of ibl/shared/split_sum.h, as shadeSplitSum), the environment as
// a skybox; offscreen (screenshots, tests) or in a GLFW window.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ibl/bake/bake.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/probe.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/render/scene.hpp"

namespace ibl::gpu {

// The scene and the bake on the device, and the pipelines that draw them.
class SceneRenderer {
 public:
  // Uploads the scene (spheres: ray traced inside a bounding polyhedron) and the bake's specular,
  // irradiance, source cubes, DFG table and SH9. The context needs a graphics queue
  // (ContextOptions::graphics).
  // probes: local light probes (loadProbes order), all of one size and level count.
  SceneRenderer(Context& context, const Scene& scene, const BakeResult& bake,
                const BakeOptions& bakeOptions, const std::vector<LocalProbe>& probes = {});
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // Renders one frame offscreen and reads it back: linear radiance and coverage, as
  // renderScene returns them. options.spp is the multisample count (rounded down to 1, 2, 4 or
  // 8, as the device supports); options.mode is ignored (always the split sum).
  RenderResult render(const Camera& camera, const RenderOptions& options, float skyboxLod = 0.0f);
  // Multisample count of the last frame.
  int samples() const;

  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

struct WindowOptions {
  Camera camera;               // the initial view; width and height: the window's size
  RenderOptions render;        // shading switches; spp: multisamples
  std::optional<float> ev100;  // none: from the first frame's average luminance
  float compensation = 0.0f;   // stops subtracted from EV100
  ToneMap toneMap = ToneMap::Aces;
  float skyboxLod = 0.0f;
  int frames = 0;  // stop after this many frames (0: when the window is closed)
  std::string title = "ibl view";
  // Called with the current view rendered offscreen (linear radiance), its EV100 and tone
  // curve when the user presses P or F12; none: the keys do nothing.
  std::function<void(const RenderResult&, float ev100, ToneMap)> screenshot;
};

struct WindowStats {
  int frames = 0;
  double meanFrameMs = 0.0;  // wall time per frame, presentation included
  std::string device;
  int samples = 0;  // MSAA samples per pixel the device allowed
};

// Opens a GLFW window and runs the interactive viewer until it is closed (Esc, Q) or after
// `frames` frames: left drag orbits, the wheel zooms, +/- change the exposure, [ and ] the
// skybox's mip level, D and S toggle the diffuse and specular terms, P or F12 takes a
// screenshot (options.screenshot), T cycles the tone curve,
// R resets the view; the title shows the frame time. Throws Error("window: ...") without a
// display.
WindowStats runViewerWindow(const Scene& scene, const BakeResult& bake,
                            const BakeOptions& bakeOptions, const WindowOptions& options,
                            const std::vector<LocalProbe>& probes = {});

}  // namespace ibl::gpu
