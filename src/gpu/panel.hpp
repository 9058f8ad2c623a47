#pragma once
// Internal: the viewer's panel (Dear ImGui, drawn by its GLFW and Vulkan back ends into the
// window's tone-mapping pass): every live setting of the window, the lights of the scene, and the
// frame's figures. What the panel and the keys change lives in ViewerControls, which the window
// reads each frame; screenshots are rendered offscreen and never show the panel.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gpu/vulkan.hpp"
#include "ibl/gpu/viewer.hpp"
#include "ibl/render/exposure.hpp"
#include "ibl/render/light.hpp"

struct GLFWwindow;

namespace ibl::gpu {

// The window's live settings, changed by the keys and the panel.
struct ViewerControls {
  bool panel = true;  // F1 toggles it
  // Where the panel was drawn last (x0, y0, x1, y1 in window pixels; zero when hidden) and
  // whether one of its menus is open: a press or a scroll there is the panel's.
  glm::vec4 panelArea{0.0f};
  bool menuOpen = false;
  bool onPanel(double x, double y) const {
    return menuOpen || (x >= panelArea.x && x < panelArea.z && y >= panelArea.y && y < panelArea.w);
  }
  // Exposure: the EV100 shown (auto exposure eases it each frame; otherwise the user sets it),
  // the compensation subtracted from it, and auto exposure's settings.
  float ev100 = 0.0f;
  float compensation = 0.0f;
  bool autoExposure = true;
  // The physical camera: with physicalCamera, EV100 follows the aperture (f-number), shutter
  // time (s) and ISO (ev100FromSettings), auto exposure off.
  bool physicalCamera = false;
  float aperture = 16.0f, shutter = 1.0f / 125.0f, iso = 100.0f;
  float adaptationSpeed = 3.0f;
  MeteringRange metering;
  ToneMap toneMap = ToneMap::Aces;
  bool bloom = true;
  float bloomStops = 3.0f;  // the bloom's threshold above the average luminance
  bool diffuse = true, specular = true;
  float skyboxLod = 0.0f, maxSkyboxLod = 0.0f;
  ViewMode view = ViewMode::RealTime;
  float split = 0.5f;                      // the split view's boundary, a share of the width
  BufferView buffer = BufferView::Shaded;  // what the real-time view shows (V cycles it)
  bool clay = false;                       // every material as clay (C)
  bool temporalAntialiasing = true;        // the real-time view's (SceneRenderer's)
  bool screenshotRequested = false;
  int timeStep = 0;  // the sun lower (-1) or higher (+1)
  // The panel's save buttons (the window writes the files) and what the last save said.
  bool saveSettingsRequested = false, saveLightsRequested = false;
  std::string status;
  // A pick asked for at this window point (the right button), and what the last one found: one
  // line per fact, empty before any.
  std::optional<glm::vec2> pickAt;
  std::string dropped;  // a file or folder dropped on the window, not yet loaded
  std::vector<std::string> picked;
  // The scene's lights as shown (edited in place); lightsChanged when the panel changed one.
  std::vector<Light> lights;
  bool lightsChanged = false;
};

// What the panel reports of the last frame.
struct PanelFigures {
  double frameMs = 0.0;
  std::string device;
  int samples = 0;
  bool timeOfDay = false;  // the sun can move (, and .)
  bool canSaveSettings = false, canSaveLights = false;
  int referenceSpp = 0;  // outside the real-time view
  float referenceNoise = 0.0f;
  // The last real-time frame's passes on the device (name, ms; empty without timestamps) and the
  // device memory the viewer holds.
  std::vector<std::pair<std::string, double>> passes;
  std::uint64_t deviceMemoryBytes = 0;
};

class Panel {
 public:
  // Sets up Dear ImGui on `window` (its GLFW callbacks chained after the window's own) and its
  // Vulkan back end for `pass` (subpass 0, one sample) with `imageCount` swapchain images; the
  // font is uploaded at once. srgbTarget: the pass writes an sRGB format, so the panel's colors
  // are decoded to linear first (they are authored in sRGB).
  Panel(Context& context, GLFWwindow* window, VkRenderPass pass, std::uint32_t imageCount,
        bool srgbTarget);
  ~Panel();
  Panel(const Panel&) = delete;
  Panel& operator=(const Panel&) = delete;

  // Builds this frame's panel from `controls` (changing them as the user does), or nothing when
  // controls.panel is off.
  void build(ViewerControls& controls, const PanelFigures& figures);
  // Records the built panel's draws into the pass being recorded.
  void record(VkCommandBuffer cmd);
  // Whether a field of the panel is being typed into (the window then leaves the keys to it).
  // Not Dear ImGui's WantCaptureKeyboard: that stays set for the frame after a click on a
  // button, and a key pressed then would be lost. The mouse: ViewerControls::onPanel.
  static bool editsText();

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
};

}  // namespace ibl::gpu
