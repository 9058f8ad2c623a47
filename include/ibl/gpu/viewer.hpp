#pragma once
// API: internal (may change without notice; the Vulkan back end of the command-line front end)
// The real-time viewer on Vulkan: the scene rasterized and shaded with the split sum of
// `ibl render` (the formulas of ibl/shared/split_sum.h, as shadeSplitSum), the environment as
// a skybox; offscreen (screenshots, tests) or in a GLFW window.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ibl/bake/bake.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/exposure.hpp"
#include "ibl/render/irradiance_volume.hpp"
#include "ibl/render/probe.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/render/scene.hpp"
#include "ibl/render/shadows.hpp"

namespace ibl::gpu {

// What the scene pass shows (kBuffer* of ibl/shared/buffer_views.h, the same values): the
// shading, or one of its inputs as display colors (no exposure or tone curve): the material's
// base color, roughness (as shaded, specular antialiasing included), metallic, world normals,
// occlusion texture; GTAO's visibility; the sun's shadow cascades; the lights per cluster as a
// heat map; the screen-space reflections' hits; the local probes' and the irradiance volume's
// influence; the validation of the materials against measured ranges.
enum class BufferView {
  Shaded = 0,
  BaseColor,
  Roughness,
  Metallic,
  Normals,
  MaterialOcclusion,
  ScreenOcclusion,
  ShadowCascades,
  LightClusters,
  ReflectionHits,
  ProbeInfluence,
  VolumeInfluence,
  Validation
};
inline constexpr int kBufferViewCount = 13;
// "shaded", "base-color", "roughness", "metallic", "normals", "occlusion", "gtao", "cascades",
// "clusters", "reflections", "probes", "volume", "validation" (`ibl view --buffer`).
const char* bufferViewName(BufferView view);
// The view of that name, or none.
std::optional<BufferView> bufferViewNamed(std::string_view name);

// The scene and the bake on the device, and the pipelines that draw them.
class SceneRenderer {
 public:
  // Uploads the scene (spheres: ray traced inside a bounding polyhedron) and the bake's specular,
  // irradiance, source cubes, DFG table and SH9. The context needs a graphics queue
  // (ContextOptions::graphics).
  // probes: local light probes (loadProbes order), all of one size and level count.
  // volume: an irradiance volume (loadVolume), composed as the CPU split sum composes
  // RenderOptions::volume (null: none; the frames then read no volume whatever options.volume
  // says, as they read the probes given here and not options.probes). Throws Error when the
  // device's 2D images are smaller than its atlases.
  // updatableVolume: whether the volume can be updated live (updateVolume, record's flag); false
  // leaves out the update's scene buffers and pipelines, which a static volume never reads.
  SceneRenderer(Context& context, const Scene& scene, const BakeResult& bake,
                const BakeOptions& bakeOptions, const std::vector<LocalProbe>& probes = {},
                const IrradianceVolume* volume = nullptr, bool updatableVolume = true);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // Renders one frame offscreen and reads it back: linear radiance and coverage, as
  // renderScene returns them. options.spp is the multisample count (rounded down to 1, 2, 4 or
  // 8, as the device supports); options.mode is ignored (always the split sum).
  RenderResult render(const Camera& camera, const RenderOptions& options, float skyboxLod = 0.0f);
  // Multisample count of the last frame.
  int samples() const;
  // The lights' shadow maps as the frame of `camera` with `options` reads them, depths read back
  // from the device (rasterized there; see docs/lights.md, "Shadows"): what ShadowMapBuilder
  // traces on the CPU. Empty (no casters) when options.realTimeShadows is not Map or the scene
  // has no lights. Draws that frame (at one sample per pixel: the next render() restores its
  // own count).
  ShadowMaps shadowMaps(const Camera& camera, const RenderOptions& options);
  // The screen-space ambient occlusion of a frame (options.screenAmbientOcclusion, on whether
  // asked or not) as the device computed it: per pixel the visibility and the bent normal in
  // world space (zero where no surface is), for comparing with screenSpaceAmbientOcclusion.
  ScreenOcclusion screenOcclusion(const Camera& camera, const RenderOptions& options);
  // The screen-space reflections of a frame (options.screenReflections, on whether asked or not)
  // as the device computed them, with the inputs its pass read: for running the CPU's
  // shared::screenSpaceReflection over the same buffers.
  struct Reflections {
    ScreenReflections reflections;  // premultiplied radiance, the share of the lobe
    ViewBuffers viewBuffers;        // as rasterized: z 0 (and normal 0) where no surface is
    Image litFrame;                 // the frame's first pass, without reflections
  };
  Reflections screenReflections(const Camera& camera, const RenderOptions& options);
  // Replaces the environment (the bake's maps and SH9) and the scene's lights, as when the time
  // of day changes: `lights` must be as many as the scene's (the sun's new direction, color and
  // illuminance; an IES light keeps its profile). Waits for the device to be idle.
  void setEnvironment(const BakeResult& bake, const BakeOptions& bakeOptions,
                      const std::vector<Light>& lights);
  // Replaces the scene's lights alone (moved, dimmed, recolored: as many as the scene's, each of
  // its type and IES profile, else Error("viewer: ...")). Waits for the device to be idle.
  void setLights(const std::vector<Light>& lights);
  // What the frames drawn from now on show (BufferView::Shaded at first). A buffer that the
  // frame's options leave out shows its neutral value: GTAO's and the reflections' none, no
  // cascades without a sun that casts shadows, no influence without probes or a volume.
  void setBufferView(BufferView view);
  // Clay: every material drawn from now on as one matte gray dielectric (base color 0.5,
  // roughness 0.6; no coat, sheen, film, anisotropy or transmission), its normal map, occlusion,
  // coverage and emission kept, so that the shapes and the light are seen alone.
  void setClay(bool clay);
  // Temporal antialiasing (Karis 2014; ibl/shared/temporal_antialiasing.h) of the shaded frames
  // drawn from now on, the window's and render()'s (a frame of it per call): each frame drawn
  // with its projection shifted by the next of kTemporalJitterPeriod sub-pixel jitters, and
  // blended, with the share kTemporalFeedback, into the history of the frames before, which is
  // reprojected through the camera's motion (the view buffers' positions, the sky's directions)
  // and clipped to the box of the frame's 3 x 3 neighborhood in YCoCg. `exposure`
  // (exposureFromEv100) puts radiance into the display's range for the blend's weights,
  // 1 / (1 + luma). Off at first. A buffer view, a new size or turning it on starts the history
  // over.
  void setTemporalAntialiasing(bool enabled, float exposure = 1.0f);
  // `frames` (>= 1) frames of a still camera, the k-th shifted by temporalJitter(k), averaged
  // with equal weights, unclipped: the pixel's box-filtered value as `frames` samples of a
  // low-discrepancy set estimate it (with options.spp multisamples each), read back as render()
  // does (`ibl view --taa N`'s screenshot). The shaded view, whatever setBufferView says.
  RenderResult renderAccumulated(const Camera& camera, const RenderOptions& options, int frames,
                                 float skyboxLod = 0.0f);
  // The GPU time of the last frame's passes (render, or the window's frame once done), in
  // order, in milliseconds, from timestamp queries: "volume update", "shadow maps", "view
  // buffers", "GTAO", "transmission frame", "reflections", "scene" (those the frame ran). Empty
  // where the device writes no timestamps.
  std::vector<std::pair<std::string, double>> passTimes() const;
  // The irradiance volume's live update (src/gpu/volume_update.hpp): `frames` frames of it,
  // lit by the lights and the environment with the shading switches of `options`, as
  // updateVolume runs them on the CPU (the same frames: the same rays); the frames drawn after
  // read the updated volume. Throws Error("view: ...") without a volume.
  void updateVolume(const Camera& camera, const RenderOptions& options, int frames);
  // The volume's atlases as the device holds them now: irradiance, distance (IrradianceVolume's
  // layout). Throws Error("view: ...") without a volume.
  std::pair<Image, Image> volumeAtlases() const;
  // The device it draws on (a bake can run there: bakeEnvironment's `device`).
  Context& context();

  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

// A new environment for a running viewer (time of day): its bake and the scene's lights.
struct EnvironmentChange {
  BakeResult bake;
  BakeOptions options;
  std::vector<Light> lights;  // as many as the scene's
  std::string label;          // for the title and the log: "sun at 35 degrees"
};

// What the window shows (M cycles through them): the real-time frame; the reference
// (gpu::PathTracer, path_tracer.hpp) accumulating while the view stands still; the difference of
// the two as `ibl compare --error-png` draws it (errorFalseColor of ibl/core/stats.hpp, the
// real-time frame judged against the reference, at kViewDifferenceScale); the left half real time
// and the right half the reference.
enum class ViewMode { RealTime = 0, Reference = 1, Difference = 2, Split = 3 };
// "real time", "reference", "difference", "split".
const char* viewModeName(ViewMode mode);
// The relative error the difference view shows as red (`ibl compare --error-scale`'s default).
inline constexpr double kViewDifferenceScale = 0.1;

// The picture of `mode` from a real-time frame and a reference of the same size: the real-time
// frame itself; the reference; errorFalseColor(realTime, reference, kViewDifferenceScale) (values
// in [0, 1] to be shown without exposure or tone curve; coverage the reference's); or the columns
// x < split * width (rounded down; split in [0, 1], 0.5 by default) of the real-time frame and
// the others of the reference, coverage likewise.
RenderResult composeView(ViewMode mode, const RenderResult& realTime, const RenderResult& reference,
                         float split = 0.5f);

// The options of the reference the viewer compares with: the real-time switches of `realTime`
// (terms, diffuse model, multiple scattering, background, environment light, ...) in
// RenderMode::Reference with `ibl render --mode reference`'s defaults (4 bounces, seed 1).
RenderOptions viewReferenceOptions(const RenderOptions& realTime);

// What the window shows, as its panel and keys left it: saved by the panel (WindowOptions::
// saveSettings) for `ibl view --settings` to show the same again, in a window or a screenshot.
struct ViewSettings {
  int width = 0, height = 0;                             // the window's size
  glm::vec3 from{0.0f}, at{0.0f}, up{0.0f, 1.0f, 0.0f};  // the orbiting camera
  float fov = 40.0f;
  bool perspective = true;
  std::optional<float> ev100;  // none: auto exposure
  float adaptationSpeed = 3.0f;
  MeteringRange metering;
  float compensation = 0.0f;
  ToneMap toneMap = ToneMap::Aces;
  std::optional<float> bloom;  // none: off
  ShadingTerms only = ShadingTerms::Both;
  float skyboxLod = 0.0f;
  ViewMode view = ViewMode::RealTime;
  float split = 0.5f;  // the split view's share of the real-time frame
  BufferView buffer = BufferView::Shaded;
  bool clay = false;
  bool temporalAntialiasing = true;
  bool panel = true;
};

struct WindowOptions {
  Camera camera;         // the initial view; width and height: the window's size
  RenderOptions render;  // shading switches; spp: multisamples
  // The exposure: a fixed EV100, or none for auto exposure (ibl/render/exposure.hpp): the first
  // frame metered on the host, then, with autoExposure, every frame's histogram counted on the
  // device (shaders/view/luminance_histogram.comp) and the exposure eased toward what it asks for
  // at adaptationSpeed (1/s; 0: at once); without autoExposure, the first frame's kept.
  std::optional<float> ev100;
  bool autoExposure = true;
  // The camera settings that fixed ev100, when they did (all > 0): the panel's physical camera
  // starts from them.
  float aperture = 0.0f, shutter = 0.0f, iso = 0.0f;
  MeteringRange metering;
  float adaptationSpeed = 3.0f;
  float compensation = 0.0f;  // stops subtracted from EV100
  ToneMap toneMap = ToneMap::Aces;
  float skyboxLod = 0.0f;
  // Bloom of the live image: the light this many stops above the average luminance the
  // exposure is set for spreads, as applyBloom (ibl/render/bloom.hpp) computes it, on the device
  // (bloomOnDevice); none: off.
  std::optional<float> bloom;
  int frames = 0;     // stop after this many frames (0: when the window is closed)
  bool panel = true;  // the panel (Dear ImGui) shown at the start; F1 toggles it
  std::string title = "ibl view";
  // Called with the current view rendered offscreen (linear radiance), its EV100 and tone
  // curve when the user presses P or F12; none: the keys do nothing. Outside the real-time view:
  // the picture shown (composeView); ViewMode::Difference's colors, and a buffer's (BufferView
  // other than Shaded), are to be written as they are.
  std::function<void(const RenderResult&, float ev100, ToneMap, ViewMode, BufferView)> screenshot;
  // Time of day: called with -1 or +1 when the user presses , or . (the sun lower / higher), and
  // the viewer's device to bake on; returns the new environment, or nothing. The title and
  // stderr show how long the change took.
  std::function<std::optional<EnvironmentChange>(int step, Context& device)> timeOfDay;
  // A file or folder dropped on the window (an .hdr, .exr or .ktx2 environment, or a bake's
  // folder): called with its path and the viewer's device; returns the new environment (the
  // scene's lights as many as before: the window keeps the panel's edits of those that are not
  // suns), or throws Error, whose message the panel and stderr show. None: drops are ignored.
  std::function<std::optional<EnvironmentChange>(const std::string& path, Context& device)>
      dropEnvironment;
  // The panel's "save settings" and "save lights" buttons: called with what the window shows, or
  // with its lights as edited (types, sizes and profiles as loaded); they return the path they
  // wrote, shown in the panel, or throw Error (its message shown). None: no button.
  std::function<std::string(const ViewSettings&)> saveSettings;
  std::function<std::string(const std::vector<Light>&)> saveLights;
  // The view the window starts in (M cycles it). Reference, difference and split views trace the
  // reference on the window's device (gpu::PathTracer, made when first shown) with
  // `reference`'s options (none: viewReferenceOptions(render); D and S still switch its terms),
  // a batch of samples per frame (1 to 16 per pixel, sized to keep a frame near 30 ms) for as long
  // as the camera, the shading switches, the window's size and the environment stay the same;
  // any change starts it over.
  ViewMode view = ViewMode::RealTime;
  std::optional<RenderOptions> reference;
  // The split view's boundary, as a share of the width from the left (composeView's split).
  float split = 0.5f;
  // The buffer the real-time view starts showing (V cycles them; SceneRenderer::setBufferView):
  // its colors shown as they are, without exposure, bloom or tone curve.
  BufferView buffer = BufferView::Shaded;
  bool clay = false;  // every material drawn as clay in the real-time view (C toggles it)
  // Temporal antialiasing of the real-time view (SceneRenderer::setTemporalAntialiasing,
  // exposed as the window is); its screenshots (P) and the frame the comparison views show are
  // kTemporalJitterPeriod jittered frames averaged (SceneRenderer::renderAccumulated).
  bool temporalAntialiasing = true;
  int referenceSpp = 0;  // the reference stops adding samples at this many per pixel (0: 1 << 20)
  // With a volume: each real-time frame runs a frame of its live update first
  // (SceneRenderer::updateVolume), so that the sun, the environment and the lights relight it;
  // false keeps the volume as baked.
  bool volumeUpdate = true;
};

struct WindowStats {
  int frames = 0;
  double meanFrameMs = 0.0;  // wall time per frame, presentation included
  std::string device;
  int samples = 0;                     // MSAA samples per pixel the device allowed
  ViewMode view = ViewMode::RealTime;  // the view shown when the window closed
  float ev100 = 0.0f;                  // the exposure then (compensation not included)
  int referenceSpp = 0;                // the reference's samples per pixel then (0: none traced)
  float referenceNoise = 0.0f;         // and its estimated relative noise (PathTracer::noise)
};

// The window's bloom run offscreen: `linear` (radiance) uploaded, bloomed by the device's passes
// (shaders/view/bloom_*.comp) as the window blooms its frames, and read back; what applyBloom
// (ibl/render/bloom.hpp) computes on the CPU, to float rounding.
Image bloomOnDevice(Context& context, const Image& linear, float ev100, float compensation);

// Auto exposure's histogram of `linear` (radiance) counted on the device
// (shaders/view/luminance_histogram.comp) as the window counts its frames, twice in a row as two
// frames would be (the second's bins returned): what luminanceHistogram
// (ibl/render/exposure.hpp) counts on the CPU.
LuminanceHistogram luminanceHistogramOnDevice(Context& context, const Image& linear);

// Opens a GLFW window and runs the interactive viewer until it is closed (Esc, Q) or after
// `frames` frames: left drag orbits, the wheel zooms, +/- change the exposure compensation,
// [ and ] the skybox's mip level, D and S toggle the diffuse and specular terms, P or F12 takes
// a screenshot (options.screenshot), T cycles the tone curve, M cycles the view (real time,
// reference, difference, split: ViewMode), V cycles the buffers (BufferView), C clay, the right
// button picks the surface under the cursor (the panel and stderr list its material), A toggles
// auto exposure, B bloom, F1 the panel
// (src/gpu/panel.hpp: every setting, the lights, saving them), R resets the view; the title
// shows the frame time,
// and outside the real-time view the view's name, the reference's samples per pixel and its
// estimated noise (PathTracer::noise, in percent). Throws Error("window: ...") without a
// display.
// probes and volume: as SceneRenderer's.
WindowStats runViewerWindow(const Scene& scene, const BakeResult& bake,
                            const BakeOptions& bakeOptions, const WindowOptions& options,
                            const std::vector<LocalProbe>& probes = {},
                            const IrradianceVolume* volume = nullptr);

}  // namespace ibl::gpu
