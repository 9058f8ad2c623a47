#include "gpu/panel.hpp"

#include <algorithm>
#include <array>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <fmt/format.h>
#include <imgui.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/shared/color.h"

namespace ibl::gpu {

namespace {

constexpr float kPanelWidth = 360.0f;

// Dear ImGui's back end reports Vulkan errors through this.
void checkImGuiVulkan(VkResult r) {
  if (r < 0) check(r, "Dear ImGui's Vulkan back end");
}

const char* lightUnit(LightType type) {
  switch (type) {
    case LightType::Point:
    case LightType::Spot:
      return "cd";
    case LightType::Sun:
      return "lx";
    default:
      return "nit";
  }
}

// Whether the light's `direction` means something (the point and the sphere shine all around).
bool hasDirection(LightType type) {
  return type != LightType::Point && type != LightType::Sphere;
}

// The light's fields the panel edits; true when one changed.
bool editLight(Light& light) {
  bool changed = false;
  // An IES light's candela are its profile's times iesScale (its `intensity` is not read).
  float& value = light.ies ? light.iesScale : light.intensity;
  const std::string label = light.ies ? std::string("profile multiplier")
                                      : fmt::format("intensity ({})", lightUnit(light.type));
  changed |=
      ImGui::DragFloat(label.c_str(), &value, std::max(value, 1.0f) * 0.01f, 0.0f, 1e9f, "%.4g");
  value = std::max(value, 0.0f);
  changed |= ImGui::ColorEdit3("color", &light.color.x,
                               ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
  // Or a lamp's correlated color temperature: the blackbody's color at luminance 1
  // (blackbodyColor), clamped into the gamut below 1900 K; the slider keeps its own value.
  float& kelvin = *ImGui::GetStateStorage()->GetFloatRef(ImGui::GetID("kelvin"), 6500.0f);
  if (ImGui::DragFloat("temperature K", &kelvin, 10.0f, 1000.0f, 40000.0f, "%.0f")) {
    kelvin = std::clamp(kelvin, 1000.0f, 40000.0f);
    light.color = glm::max(blackbodyColor(kelvin), glm::vec3(0.0f));
    changed = true;
  }
  if (light.type != LightType::Sun)
    changed |= ImGui::DragFloat3("position", &light.position.x, 0.01f, -1e4f, 1e4f, "%.3f");
  if (hasDirection(light.type)) {
    glm::vec3 d = light.direction;
    if (ImGui::DragFloat3("direction", &d.x, 0.01f, -1.0f, 1.0f, "%.3f") &&
        glm::length(d) > 1e-3f) {
      light.direction = glm::normalize(d);
      // A rect's up stays orthogonal to its direction.
      glm::vec3 up = light.up - glm::dot(light.up, light.direction) * light.direction;
      if (glm::length(up) < 1e-3f)
        up = glm::cross(light.direction, std::abs(light.direction.x) < 0.9f
                                             ? glm::vec3(1.0f, 0.0f, 0.0f)
                                             : glm::vec3(0.0f, 1.0f, 0.0f));
      light.up = glm::normalize(up);
      changed = true;
    }
  }
  return changed;
}

}  // namespace

Panel::Panel(Context& context, GLFWwindow* window, VkRenderPass pass, std::uint32_t imageCount,
             bool srgbTarget) {
  auto& c = context.impl();
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini in the user's folder
  ImGui::StyleColorsDark();
  if (srgbTarget)
    for (ImVec4& color : ImGui::GetStyle().Colors) {
      const glm::vec3 linear = shared::srgbToLinear(glm::vec3(color.x, color.y, color.z));
      color = ImVec4(linear.x, linear.y, linear.z, color.w);
    }
  ImGui_ImplGlfw_InitForVulkan(window, true);
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = c.instance;
  info.PhysicalDevice = c.physical;
  info.Device = c.device;
  info.QueueFamily = c.family;
  info.Queue = c.queue;
  // The font's one descriptor set.
  pool_ = createDescriptorPool(c.device, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1);
  info.DescriptorPool = pool_;
  info.Subpass = 0;
  info.MinImageCount = std::max(imageCount, 2u);
  info.ImageCount = std::max(imageCount, 2u);
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkImGuiVulkan;
  ImGui_ImplVulkan_Init(&info, pass);
  c.submitAndWait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  device_ = c.device;
}

Panel::~Panel() {
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  if (pool_) vkDestroyDescriptorPool(device_, pool_, nullptr);
}

bool Panel::editsText() {
  return ImGui::GetCurrentContext() && ImGui::GetIO().WantTextInput;
}

void Panel::build(ViewerControls& s, const PanelFigures& f) {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  s.panelArea = glm::vec4(0.0f);
  if (s.panel) {
    // At the top left, as tall as its content up to the window's height (then it scrolls).
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSizeConstraints(ImVec2(kPanelWidth, 0.0f),
                                        ImVec2(kPanelWidth, ImGui::GetIO().DisplaySize.y));
    ImGui::Begin("ibl view (F1 hides)", &s.panel, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::Text("%.2f ms/frame (%.0f fps), %dx MSAA", f.frameMs, 1000.0 / std::max(f.frameMs, 1e-3),
                f.samples);
    ImGui::TextUnformatted(f.device.c_str());
    if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) {
      // Every control keeps its place (those that do not apply are grayed out), so that the
      // panel does not jump as they are switched.
      if (ImGui::Checkbox("auto exposure (A)", &s.autoExposure) && s.autoExposure)
        s.physicalCamera = false;
      ImGui::BeginDisabled(s.autoExposure || s.physicalCamera);
      ImGui::SliderFloat(s.autoExposure ? "EV100 (metered)" : "EV100", &s.ev100, -6.0f, 20.0f,
                         "%.2f");
      ImGui::EndDisabled();
      ImGui::BeginDisabled(!s.autoExposure);
      ImGui::SliderFloat("adaptation /s", &s.adaptationSpeed, 0.0f, 10.0f, "%.1f");
      ImGui::DragFloatRange2("metering %", &s.metering.low, &s.metering.high, 0.5f, 0.0f, 100.0f,
                             "%.1f");
      s.metering.low = std::clamp(s.metering.low, 0.0f, 99.5f);
      s.metering.high = std::clamp(s.metering.high, s.metering.low + 0.5f, 100.0f);
      ImGui::EndDisabled();
      ImGui::SliderFloat("compensation (+ -)", &s.compensation, -6.0f, 6.0f, "%.1f stops");
      int curve = static_cast<int>(s.toneMap);
      const std::array<const char*, 3> curves{"none", "ACES", "filmic"};
      if (ImGui::Combo("tone curve (T)", &curve, curves.data(), static_cast<int>(curves.size())))
        s.toneMap = static_cast<ToneMap>(curve);
      ImGui::Checkbox("bloom (B)", &s.bloom);
      ImGui::BeginDisabled(!s.bloom);
      ImGui::SliderFloat("bloom above", &s.bloomStops, -4.0f, 10.0f, "%.1f stops");
      ImGui::EndDisabled();
    }
    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
      int view = static_cast<int>(s.view);
      const std::array<const char*, 4> views{"real time", "reference", "difference", "split"};
      if (ImGui::Combo("view (M)", &view, views.data(), static_cast<int>(views.size())))
        s.view = static_cast<ViewMode>(view);
      // Never both terms off.
      if (ImGui::Checkbox("diffuse", &s.diffuse) && !s.diffuse) s.specular = true;
      ImGui::SameLine();
      if (ImGui::Checkbox("specular", &s.specular) && !s.specular) s.diffuse = true;
      ImGui::SliderFloat("skybox mip", &s.skyboxLod, 0.0f, s.maxSkyboxLod, "%.1f");
      if (ImGui::Button("screenshot (P)")) s.screenshotRequested = true;
      if (f.canSaveSettings) {
        ImGui::SameLine();
        if (ImGui::Button("save settings")) s.saveSettingsRequested = true;
      }
      // The buffers, in the real-time view (their colors shown as they are).
      ImGui::BeginDisabled(s.view != ViewMode::RealTime);
      int buffer = static_cast<int>(s.buffer);
      std::array<const char*, kBufferViewCount> buffers{};
      for (int i = 0; i < kBufferViewCount; ++i)
        buffers[static_cast<std::size_t>(i)] = bufferViewName(static_cast<BufferView>(i));
      if (ImGui::Combo("buffer (V)", &buffer, buffers.data(), kBufferViewCount))
        s.buffer = static_cast<BufferView>(buffer);
      ImGui::Checkbox("clay (C)", &s.clay);
      ImGui::Checkbox("temporal antialiasing", &s.temporalAntialiasing);
      ImGui::EndDisabled();
      ImGui::BeginDisabled(s.view != ViewMode::Split);
      ImGui::SliderFloat("split at", &s.split, 0.0f, 1.0f, "%.2f of the width");
      ImGui::EndDisabled();
      if (s.view != ViewMode::RealTime)
        ImGui::Text("reference: %d spp, noise %.2f %%", f.referenceSpp, 100.0f * f.referenceNoise);
    }
    if (f.timeOfDay && ImGui::CollapsingHeader("Sky", ImGuiTreeNodeFlags_DefaultOpen)) {
      if (ImGui::Button("sun lower (,)")) s.timeStep = -1;
      ImGui::SameLine();
      if (ImGui::Button("sun higher (.)")) s.timeStep = 1;
    }
    if (!s.lights.empty() &&
        ImGui::CollapsingHeader(fmt::format("Lights ({})", s.lights.size()).c_str())) {
      for (std::size_t i = 0; i < s.lights.size(); ++i) {
        Light& light = s.lights[i];
        const std::string label =
            fmt::format("{} {}{}{}###light{}", i + 1, lightTypeName(light.type),
                        light.name.empty() ? "" : ": ", light.name, i);
        if (ImGui::TreeNode(label.c_str())) {
          ImGui::PushID(static_cast<int>(i));
          s.lightsChanged |= editLight(light);
          ImGui::PopID();
          ImGui::TreePop();
        }
      }
      if (f.canSaveLights && ImGui::Button("save lights")) s.saveLightsRequested = true;
    }
    // Last, so that the sections above keep their places when they open.
    if (!s.picked.empty() &&
        ImGui::CollapsingHeader("Picked (right button)", ImGuiTreeNodeFlags_DefaultOpen))
      for (const std::string& line : s.picked) ImGui::TextWrapped("%s", line.c_str());
    if (ImGui::CollapsingHeader("GPU")) {
      double total = 0.0;
      for (const auto& [name, ms] : f.passes) {
        ImGui::Text("%-20s %7.2f ms", name.c_str(), ms);
        total += ms;
      }
      if (f.passes.empty())
        ImGui::TextUnformatted("no timestamps on this device");
      else
        ImGui::Text("%-20s %7.2f ms", "total", total);
      ImGui::Text("device memory %.1f MB", static_cast<double>(f.deviceMemoryBytes) / 1048576.0);
    }
    if (ImGui::CollapsingHeader("Physical camera")) {
      if (ImGui::Checkbox("expose by aperture, shutter, ISO", &s.physicalCamera) &&
          s.physicalCamera)
        s.autoExposure = false;
      ImGui::BeginDisabled(!s.physicalCamera);
      ImGui::SliderFloat("aperture f/", &s.aperture, 1.0f, 32.0f, "%.1f",
                         ImGuiSliderFlags_Logarithmic);
      float perSecond = 1.0f / s.shutter;  // shown as 1/N s
      if (ImGui::SliderFloat("shutter 1/s", &perSecond, 1.0f / 30.0f, 8000.0f, "%.3g",
                             ImGuiSliderFlags_Logarithmic))
        s.shutter = 1.0f / perSecond;
      ImGui::SliderFloat("ISO", &s.iso, 25.0f, 25600.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
      ImGui::EndDisabled();
      if (s.physicalCamera) s.ev100 = ev100FromSettings(s.aperture, s.shutter, s.iso);
    }
    if (!s.status.empty()) ImGui::TextWrapped("%s", s.status.c_str());
    const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    s.panelArea = glm::vec4(at.x, at.y, at.x + size.x, at.y + size.y);
    ImGui::End();
  }
  // An open menu (a combo's list) reaches beyond the panel: the pointer belongs to it anywhere.
  s.menuOpen = ImGui::IsPopupOpen(nullptr, ImGuiPopupFlags_AnyPopupId);
  ImGui::Render();
}

void Panel::record(VkCommandBuffer cmd) {
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
}

}  // namespace ibl::gpu
