// The interactive viewer: a GLFW window, a swapchain, the scene renderer, the bloom's compute
// passes (gpu/bloom.hpp) and a tone-mapping pass; the reference (gpu::PathTracer) and the views
// that show it (ViewMode), uploaded into an image the same passes read.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "gpu/bloom.hpp"
#include "gpu/exposure.hpp"
#include "gpu/panel.hpp"
#include "gpu/scene_renderer.hpp"
#include "ibl/core/error.hpp"
#include "ibl/core/stats.hpp"
#include "ibl/gpu/path_tracer.hpp"
#include "ibl/shared/temporal_antialiasing.h"
#include "render/ray_tracer.hpp"

namespace ibl::gpu {

namespace {

// What the user changes with the mouse, the keys and the panel.
struct Interaction : ViewerControls {
  glm::vec3 target{0.0f};
  float yaw = 0.0f, pitch = 0.0f, distance = 1.0f;  // camera = target + distance * dir(yaw, pitch)
  bool dragging = false;
  double lastX = 0.0, lastY = 0.0;
  Camera initial;

  void orbitFrom(const Camera& c) {
    target = c.at;
    const glm::vec3 offset = c.from - c.at;
    distance = std::max(glm::length(offset), 1e-4f);
    yaw = std::atan2(offset.x, offset.z);
    pitch = std::asin(std::clamp(offset.y / distance, -1.0f, 1.0f));
  }
  // What the window shows now, for --settings.
  ViewSettings settings(int width, int height) const {
    ViewSettings v;
    const Camera c = camera(width, height);
    v.width = width;
    v.height = height;
    v.from = c.from;
    v.at = c.at;
    v.up = c.up;
    v.fov = c.yfovDegrees;
    v.perspective = c.perspective;
    if (!autoExposure) v.ev100 = ev100;
    v.adaptationSpeed = adaptationSpeed;
    v.metering = metering;
    v.compensation = compensation;
    v.toneMap = toneMap;
    if (bloom) v.bloom = bloomStops;
    v.only = diffuse && specular ? ShadingTerms::Both
             : diffuse           ? ShadingTerms::Diffuse
                                 : ShadingTerms::Specular;
    v.skyboxLod = skyboxLod;
    v.view = view;
    v.split = split;
    v.buffer = view == ViewMode::RealTime ? buffer : BufferView::Shaded;
    v.clay = view == ViewMode::RealTime && clay;
    v.temporalAntialiasing = temporalAntialiasing;
    v.panel = panel;
    return v;
  }
  Camera camera(int width, int height) const {
    Camera c = initial;
    c.width = width;
    c.height = height;
    c.at = target;
    c.from = target + distance * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                           std::cos(pitch) * std::cos(yaw));
    c.up = glm::vec3(0.0f, 1.0f, 0.0f);
    return c;
  }
};

const char* toneMapName(ToneMap t) {
  return t == ToneMap::None ? "no tone curve" : t == ToneMap::Aces ? "ACES" : "filmic";
}

void onKey(GLFWwindow* window, int key, int, int action, int) {
  if ((action != GLFW_PRESS && action != GLFW_REPEAT) || Panel::editsText()) return;
  auto& s = *static_cast<Interaction*>(glfwGetWindowUserPointer(window));
  switch (key) {
    case GLFW_KEY_F1:
      if (action == GLFW_PRESS) s.panel = !s.panel;
      break;
    case GLFW_KEY_A:
      if (action == GLFW_PRESS) {
        s.autoExposure = !s.autoExposure;
        if (s.autoExposure) s.physicalCamera = false;
      }
      break;
    case GLFW_KEY_B:
      if (action == GLFW_PRESS) s.bloom = !s.bloom;
      break;
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q:
      glfwSetWindowShouldClose(window, GLFW_TRUE);
      break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
      s.compensation += 0.5f;
      break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
      s.compensation -= 0.5f;
      break;
    case GLFW_KEY_RIGHT_BRACKET:
      s.skyboxLod = std::min(s.skyboxLod + 0.5f, s.maxSkyboxLod);
      break;
    case GLFW_KEY_LEFT_BRACKET:
      s.skyboxLod = std::max(s.skyboxLod - 0.5f, 0.0f);
      break;
    case GLFW_KEY_D:
      if (s.specular) s.diffuse = !s.diffuse;  // never both off
      break;
    case GLFW_KEY_S:
      if (s.diffuse) s.specular = !s.specular;
      break;
    case GLFW_KEY_T:
      s.toneMap = s.toneMap == ToneMap::Aces     ? ToneMap::Filmic
                  : s.toneMap == ToneMap::Filmic ? ToneMap::None
                                                 : ToneMap::Aces;
      break;
    case GLFW_KEY_R:
      s.orbitFrom(s.initial);
      break;
    case GLFW_KEY_M:
      if (action == GLFW_PRESS) s.view = static_cast<ViewMode>((static_cast<int>(s.view) + 1) % 4);
      break;
    case GLFW_KEY_V:
      if (action == GLFW_PRESS)
        s.buffer = static_cast<BufferView>((static_cast<int>(s.buffer) + 1) % kBufferViewCount);
      break;
    case GLFW_KEY_C:
      if (action == GLFW_PRESS) s.clay = !s.clay;
      break;
    case GLFW_KEY_COMMA:
      s.timeStep = -1;
      break;
    case GLFW_KEY_PERIOD:
      s.timeStep = 1;
      break;
    case GLFW_KEY_P:
    case GLFW_KEY_F12:
      if (action == GLFW_PRESS) s.screenshotRequested = true;
      break;
    default:
      break;
  }
}

void onMouseButton(GLFWwindow* window, int button, int action, int) {
  auto& s = *static_cast<Interaction*>(glfwGetWindowUserPointer(window));
  // The right button picks the surface under the cursor (its material, in the panel).
  if (button == GLFW_MOUSE_BUTTON_RIGHT && action == GLFW_PRESS && !s.onPanel(s.lastX, s.lastY))
    s.pickAt = glm::vec2(static_cast<float>(s.lastX), static_cast<float>(s.lastY));
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  // The drag starts where the events last put the cursor (not where it is now: the events of
  // a fast drag may all be queued before the press is handled), unless that is on the panel.
  s.dragging = action == GLFW_PRESS && !s.onPanel(s.lastX, s.lastY);
}

void onCursor(GLFWwindow* window, double x, double y) {
  auto& s = *static_cast<Interaction*>(glfwGetWindowUserPointer(window));
  if (s.dragging) {
    s.yaw -= 0.006f * static_cast<float>(x - s.lastX);
    s.pitch = std::clamp(s.pitch + 0.006f * static_cast<float>(y - s.lastY), -1.55f, 1.55f);
  }
  s.lastX = x;
  s.lastY = y;
}

// A file (or folder) dropped on the window: the first, for the loop to load.
void onDrop(GLFWwindow* window, int count, const char** paths) {
  auto& s = *static_cast<Interaction*>(glfwGetWindowUserPointer(window));
  if (count > 0 && paths[0]) s.dropped = paths[0];
}

void onScroll(GLFWwindow* window, double, double dy) {
  auto& s = *static_cast<Interaction*>(glfwGetWindowUserPointer(window));
  if (s.onPanel(s.lastX, s.lastY)) return;
  s.distance *= std::pow(0.9f, static_cast<float>(dy));
}

// The swapchain and what hangs off it: the tone-mapping pass's framebuffers.
struct Swapchain {
  VkDevice device = VK_NULL_HANDLE;
  VkSwapchainKHR handle = VK_NULL_HANDLE;
  VkExtent2D extent{};
  std::vector<VkImage> images;
  std::vector<VkImageView> views;
  std::vector<VkFramebuffer> framebuffers;
  // Signaled when the frame drawn into image i is complete, waited on by its presentation: one
  // per image, as a presentation may still wait on one while the next frame is submitted.
  std::vector<VkSemaphore> rendered;

  void destroy() {
    for (VkSemaphore s : rendered) vkDestroySemaphore(device, s, nullptr);
    rendered.clear();
    for (VkFramebuffer f : framebuffers) vkDestroyFramebuffer(device, f, nullptr);
    for (VkImageView v : views) vkDestroyImageView(device, v, nullptr);
    framebuffers.clear();
    views.clear();
    images.clear();
    if (handle) vkDestroySwapchainKHR(device, handle, nullptr);
    handle = VK_NULL_HANDLE;
  }
};

// Everything the window owns, destroyed in reverse order whatever happens.
struct WindowResources {
  GLFWwindow* window = nullptr;
  std::unique_ptr<Context> context;
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  std::unique_ptr<SceneRenderer> renderer;
  std::unique_ptr<DeviceBloom> bloom;          // with WindowOptions::bloom
  std::unique_ptr<DeviceHistogram> histogram;  // auto exposure's
  std::unique_ptr<Panel> panel;                // after the callbacks it chains
  std::unique_ptr<PathTracer> tracer;          // made when a view first shows the reference
  // Outside the real-time view: the picture shown (composeView), uploaded from the host and
  // read by the bloom and the tone-mapping pass in place of the scene renderer's output.
  std::unique_ptr<DeviceImage> shown;
  Swapchain swapchain;
  VkRenderPass pass = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
  VkSampler sampler = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkSemaphore acquired = VK_NULL_HANDLE;
  VkFence done = VK_NULL_HANDLE;

  ~WindowResources() {
    if (context) {
      VkDevice d = context->impl().device;
      vkDeviceWaitIdle(d);
      panel.reset();
      bloom.reset();
      histogram.reset();
      shown.reset();
      tracer.reset();
      renderer.reset();
      swapchain.destroy();
      vkDestroyFence(d, done, nullptr);
      vkDestroySemaphore(d, acquired, nullptr);
      vkDestroyDescriptorPool(d, pool, nullptr);
      vkDestroySampler(d, sampler, nullptr);
      vkDestroyPipeline(d, pipeline, nullptr);
      vkDestroyPipelineLayout(d, pipelineLayout, nullptr);
      vkDestroyDescriptorSetLayout(d, setLayout, nullptr);
      vkDestroyShaderModule(d, vert, nullptr);
      vkDestroyShaderModule(d, frag, nullptr);
      vkDestroyRenderPass(d, pass, nullptr);
      if (surface) vkDestroySurfaceKHR(context->impl().instance, surface, nullptr);
      context.reset();
    }
    if (window) glfwDestroyWindow(window);
    glfwTerminate();
  }
};

VkSurfaceFormatKHR chooseSurfaceFormat(VkPhysicalDevice physical, VkSurfaceKHR surface) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(count);
  vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, formats.data());
  if (formats.empty()) fail("window", "the surface offers no formats");
  for (const auto& f : formats)
    if ((f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) &&
        f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
      return f;
  return formats[0];
}

bool encodesSrgb(VkFormat f) {
  return f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_R8G8B8A8_SRGB ||
         f == VK_FORMAT_A8B8G8R8_SRGB_PACK32;
}

void createSwapchain(WindowResources& r, VkSurfaceFormatKHR format) {
  auto& c = r.context->impl();
  VkSurfaceCapabilitiesKHR caps;
  check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(c.physical, r.surface, &caps),
        "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == 0xffffffffu) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(r.window, &w, &h);
    extent = {std::clamp(static_cast<std::uint32_t>(w), caps.minImageExtent.width,
                         caps.maxImageExtent.width),
              std::clamp(static_cast<std::uint32_t>(h), caps.minImageExtent.height,
                         caps.maxImageExtent.height)};
  }
  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = r.surface;
  info.minImageCount = caps.maxImageCount > 0 ? std::min(caps.minImageCount + 1, caps.maxImageCount)
                                              : caps.minImageCount + 1;
  info.imageFormat = format.format;
  info.imageColorSpace = format.colorSpace;
  info.imageExtent = extent;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always available
  info.clipped = VK_TRUE;
  info.oldSwapchain = VK_NULL_HANDLE;
  Swapchain& s = r.swapchain;
  s.device = c.device;
  s.extent = extent;
  check(vkCreateSwapchainKHR(c.device, &info, nullptr, &s.handle), "vkCreateSwapchainKHR");
  std::uint32_t count = 0;
  vkGetSwapchainImagesKHR(c.device, s.handle, &count, nullptr);
  s.images.resize(count);
  vkGetSwapchainImagesKHR(c.device, s.handle, &count, s.images.data());
  for (VkImage image : s.images) {
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format.format;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view;
    check(vkCreateImageView(c.device, &viewInfo, nullptr, &view), "vkCreateImageView");
    s.views.push_back(view);
    s.framebuffers.push_back(createFramebuffer(c.device, r.pass, {&view, 1},
                                               static_cast<int>(extent.width),
                                               static_cast<int>(extent.height)));
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore rendered;
    check(vkCreateSemaphore(c.device, &semaphoreInfo, nullptr, &rendered), "vkCreateSemaphore");
    s.rendered.push_back(rendered);
  }
}

void createTonemapPass(WindowResources& r, VkFormat format) {
  auto& c = r.context->impl();
  const VkAttachmentDescription attachment =
      attachmentDescription(format, VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_STORE,
                            VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
  const VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  // The swapchain image is acquired at the color output stage (the submission waits there).
  const VkSubpassDependency dependency{VK_SUBPASS_EXTERNAL,
                                       0,
                                       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                       0,
                                       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                       0};
  r.pass = createRenderPass(c.device, {&attachment, 1}, subpass, {&dependency, 1});

  const VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                             VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = 1;
  setInfo.pBindings = &binding;
  check(vkCreateDescriptorSetLayout(c.device, &setInfo, nullptr, &r.setLayout),
        "vkCreateDescriptorSetLayout");
  const VkPushConstantRange push{VK_SHADER_STAGE_FRAGMENT_BIT, 0, 12};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &r.setLayout;
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &push;
  check(vkCreatePipelineLayout(c.device, &layoutInfo, nullptr, &r.pipelineLayout),
        "vkCreatePipelineLayout");
  r.vert = c.shaderModule("fullscreen_vert");
  r.frag = c.shaderModule("tonemap_frag");
  GraphicsPipelineDescription p;
  p.vertex = r.vert;
  p.fragment = r.frag;
  p.layout = r.pipelineLayout;
  p.renderPass = r.pass;
  r.pipeline = createGraphicsPipeline(c.device, p);
  VkSamplerCreateInfo samplerInfo{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  samplerInfo.magFilter = samplerInfo.minFilter = VK_FILTER_NEAREST;
  samplerInfo.addressModeU = samplerInfo.addressModeV = samplerInfo.addressModeW =
      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  check(vkCreateSampler(c.device, &samplerInfo, nullptr, &r.sampler), "vkCreateSampler");
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &size;
  check(vkCreateDescriptorPool(c.device, &poolInfo, nullptr, &r.pool), "vkCreateDescriptorPool");
}

// Uploads `picture` into `image` (made, or made again, at its size: RGBA32F the bloom can copy
// from), leaving it shader-readable. The device must not be reading the old image.
void uploadPicture(Context& context, std::unique_ptr<DeviceImage>& image, const Image& picture) {
  if (!image || image->description().width != static_cast<std::uint32_t>(picture.width) ||
      image->description().height != static_cast<std::uint32_t>(picture.height)) {
    image.reset();
    image = std::make_unique<DeviceImage>(context, radianceImage(picture.width, picture.height));
  }
  uploadRadiance(context, *image, picture);
}

// What the surface at framebuffer point `pixel` of `camera`'s view is made of, as the CPU's
// surfaceAt reads it (textures, normal map, the side the camera sees): a line per fact for the
// panel, or one saying that nothing is there.
std::vector<std::string> pickedSurface(const Scene& scene, const RayTracer& tracer,
                                       const Camera& camera, glm::vec2 pixel) {
  const Ray ray = camera.generateRay(pixel.x, pixel.y);
  const RayTracer::Hit hit = tracer.intersect(ray);
  const glm::ivec2 at(glm::floor(pixel));
  if (!hit.found) return {fmt::format("pixel ({}, {}): no surface", at.x, at.y)};
  const SurfacePoint p = surfaceAt(scene, tracer, hit, ray);
  const auto v3 = [](glm::vec3 v) { return fmt::format("{:.3f}, {:.3f}, {:.3f}", v.x, v.y, v.z); };
  std::string object;
  int material = 0;
  if (tracer.isSphere(hit.geometry)) {
    object = fmt::format("sphere {}", hit.primitive);
    material = scene.spheres[hit.primitive].material;
  } else {
    const Mesh& m = scene.meshes[hit.geometry];
    object = fmt::format("mesh {}{}, triangle {}", hit.geometry,
                         m.names.empty() ? "" : " \"" + m.names.front() + "\"", hit.primitive);
    material = m.material;
  }
  std::vector<std::string> lines = {
      fmt::format("pixel ({}, {}), {:.3f} away: {}", at.x, at.y, hit.t, object),
      fmt::format("material {}", material),
      "position " + v3(p.position),
      "shading normal " + v3(p.normal),
      "base color " + v3(p.baseColor) + " (linear)",
      fmt::format("metallic {:.3f}, roughness {:.3f}, occlusion {:.3f}", p.metallic, p.roughness,
                  p.occlusion),
      fmt::format("ior {:.3f}, specular {:.3f}, specular color ", p.ior, p.specular) +
          v3(p.specularColor),
      "emission " + v3(p.emissive) + " nits"};
  if (p.clearcoat > 0.0f)
    lines.push_back(
        fmt::format("clear coat {:.3f}, roughness {:.3f}", p.clearcoat, p.clearcoatRoughness));
  if (p.sheenColor != glm::vec3(0.0f))
    lines.push_back("sheen " + v3(p.sheenColor) +
                    fmt::format(", roughness {:.3f}", p.sheenRoughness));
  if (p.transmission > 0.0f)
    lines.push_back(fmt::format("transmission {:.3f}, thickness {:.3f}{}", p.transmission,
                                p.thickness, p.volume ? " (volume)" : " (thin wall)"));
  if (p.iridescence > 0.0f)
    lines.push_back(fmt::format("iridescence {:.3f}, ior {:.3f}, thickness {:.0f} nm",
                                p.iridescence, p.iridescenceIor, p.iridescenceThickness));
  if (p.anisotropy > 0.0f)
    lines.push_back(fmt::format("anisotropy {:.3f} along ", p.anisotropy) +
                    v3(p.anisotropyTangent));
  return lines;
}

}  // namespace

const char* viewModeName(ViewMode mode) {
  switch (mode) {
    case ViewMode::RealTime:
      return "real time";
    case ViewMode::Reference:
      return "reference";
    case ViewMode::Difference:
      return "difference";
    case ViewMode::Split:
      return "split";
  }
  return "?";
}

RenderResult composeView(ViewMode mode, const RenderResult& realTime, const RenderResult& reference,
                         float split) {
  if (mode == ViewMode::RealTime) return realTime;
  if (mode == ViewMode::Reference) return reference;
  const Image& a = realTime.color;
  const Image& b = reference.color;
  if (a.width != b.width || a.height != b.height || realTime.alpha.size() != reference.alpha.size())
    fail("view", fmt::format("the real-time frame is {}x{} but the reference {}x{}", a.width,
                             a.height, b.width, b.height));
  RenderResult out = reference;
  if (mode == ViewMode::Difference) {
    out.color = errorFalseColor(a, b, kViewDifferenceScale);
    return out;
  }
  const int columns = static_cast<int>(std::clamp(split, 0.0f, 1.0f) *
                                       static_cast<float>(a.width));  // rounded down
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < std::min(columns, a.width); ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * a.width + x;
      out.color.pixels[i] = a.pixels[i];
      if (i < out.alpha.size()) out.alpha[i] = realTime.alpha[i];
    }
  return out;
}

RenderOptions viewReferenceOptions(const RenderOptions& realTime) {
  RenderOptions r = realTime;
  r.mode = RenderMode::Reference;
  r.bounces = 4;
  r.seed = 1;
  r.spp = 0;  // progressive: the pixels' positions are jittered (1 would trace their centers)
  r.shadows = false;  // as `ibl render --mode reference` without --shadows (bounces trace them)
  r.noiseThreshold = 0.0f;
  r.aoRays = 0;
  r.probes = nullptr;  // the reference reads none
  r.volume = nullptr;
  r.shadowMaps = nullptr;
  r.screenOcclusion = nullptr;
  r.screenReflection = nullptr;
  return r;
}

WindowStats runViewerWindow(const Scene& scene, const BakeResult& bake,
                            const BakeOptions& bakeOptions, const WindowOptions& o,
                            const std::vector<LocalProbe>& probes, const IrradianceVolume* volume) {
  WindowResources r;
  if (!glfwInit()) fail("window", "cannot open a window (no display?); use --screenshot");
  if (!glfwVulkanSupported()) fail("window", "GLFW finds no Vulkan loader for windows");
  ContextOptions co;
  std::uint32_t extensionCount = 0;
  const char** extensions = glfwGetRequiredInstanceExtensions(&extensionCount);
  for (std::uint32_t i = 0; i < extensionCount; ++i)
    co.instanceExtensions.emplace_back(extensions[i]);
  co.graphics = true;
  co.swapchain = true;
  r.context = Context::create(co);
  auto& c = r.context->impl();
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  r.window = glfwCreateWindow(o.camera.width, o.camera.height, o.title.c_str(), nullptr, nullptr);
  if (!r.window) fail("window", "cannot create a window");
  check(glfwCreateWindowSurface(c.instance, r.window, nullptr, &r.surface),
        "glfwCreateWindowSurface");
  VkBool32 presentable = VK_FALSE;
  vkGetPhysicalDeviceSurfaceSupportKHR(c.physical, c.family, r.surface, &presentable);
  if (!presentable) fail("window", fmt::format("{} cannot present to this window", c.info.name));
  const VkSurfaceFormatKHR format = chooseSurfaceFormat(c.physical, r.surface);
  createTonemapPass(r, format.format);
  createSwapchain(r, format);
  r.renderer = std::make_unique<SceneRenderer>(*r.context, scene, bake, bakeOptions, probes, volume,
                                               o.volumeUpdate);
  auto& renderer = r.renderer->impl();
  const int samples = renderer.supportedSamples(std::max(o.render.spp, 1));

  Interaction state;
  state.initial = o.camera;
  state.orbitFrom(o.camera);
  state.compensation = o.compensation;
  state.autoExposure = !o.ev100 && o.autoExposure;
  state.adaptationSpeed = o.adaptationSpeed;
  state.metering = o.metering;
  state.bloom = o.bloom.has_value();
  state.bloomStops = o.bloom.value_or(3.0f);
  state.panel = o.panel;
  state.lights = scene.lights;
  state.skyboxLod = o.skyboxLod;
  state.toneMap = o.toneMap;
  state.maxSkyboxLod = renderer.scene.skyboxMaxLod();
  state.diffuse = o.render.only != ShadingTerms::Specular;
  state.specular = o.render.only != ShadingTerms::Diffuse;
  state.view = o.view;
  state.buffer = o.buffer;
  state.clay = o.clay;
  state.temporalAntialiasing = o.temporalAntialiasing;
  state.split = std::clamp(o.split, 0.0f, 1.0f);
  if (o.aperture > 0.0f && o.shutter > 0.0f && o.iso > 0.0f) {
    state.physicalCamera = true;
    state.aperture = o.aperture;
    state.shutter = o.shutter;
    state.iso = o.iso;
  }
  // The exposure: fixed, or the first frame metered here and then, with auto exposure, each
  // frame's histogram (counted on the device with the frame, read once its fence has signaled).
  state.ev100 =
      o.ev100 ? *o.ev100
              : meteredEv100(
                    luminanceHistogram(r.renderer
                                           ->render(state.camera(o.camera.width, o.camera.height),
                                                    o.render, o.skyboxLod)
                                           .color),
                    o.metering, 0.0f);
  r.histogram = std::make_unique<DeviceHistogram>(*r.context);
  bool histogramRecorded = false;
  // The passes of the last real-time frame, timed on the device (SceneRenderer::passTimes and the
  // window's own, marked after them).
  std::vector<std::pair<std::string, double>> passTimes;
  bool timedFrame = false;
  std::unique_ptr<RayTracer> pickTracer;  // the scene on the CPU, for the right button's picks
  glfwSetWindowUserPointer(r.window, &state);
  glfwSetKeyCallback(r.window, onKey);
  glfwSetMouseButtonCallback(r.window, onMouseButton);
  glfwSetCursorPosCallback(r.window, onCursor);
  glfwSetScrollCallback(r.window, onScroll);
  glfwSetDropCallback(r.window, onDrop);
  r.panel = std::make_unique<Panel>(*r.context, r.window, r.pass,
                                    static_cast<std::uint32_t>(r.swapchain.images.size()),
                                    encodesSrgb(format.format));

  VkDescriptorSet set;
  VkDescriptorSetAllocateInfo setAlloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  setAlloc.descriptorPool = r.pool;
  setAlloc.descriptorSetCount = 1;
  setAlloc.pSetLayouts = &r.setLayout;
  check(vkAllocateDescriptorSets(c.device, &setAlloc, &set), "vkAllocateDescriptorSets");
  VkCommandBufferAllocateInfo cmdAlloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cmdAlloc.commandPool = c.pool;
  cmdAlloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cmdAlloc.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(c.device, &cmdAlloc, &r.cmd), "vkAllocateCommandBuffers");
  VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  check(vkCreateSemaphore(c.device, &semaphoreInfo, nullptr, &r.acquired), "vkCreateSemaphore");
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  fenceInfo.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  check(vkCreateFence(c.device, &fenceInfo, nullptr, &r.done), "vkCreateFence");

  WindowStats stats;
  stats.device = c.info.name;
  stats.samples = samples;
  using Clock = std::chrono::steady_clock;
  auto last = Clock::now(), lastTitle = last;
  double windowMs = 0.0, totalMs = 0.0, lastFrameMs = 0.0;
  int windowFrames = 0;
  // The reference, and what it was started for (a change of any starts it over); the real-time
  // frame the difference and split views compare it with, and what it was drawn for; the
  // picture those views show (composeView), uploaded into r.shown when it changes.
  const Scene* referenceScene = &scene;
  const BakeResult* referenceBake = &bake;
  const BakeOptions* referenceBakeOptions = &bakeOptions;
  Scene changedScene;  // the scene with the lights of the last time-of-day change
  std::optional<EnvironmentChange> environment;
  int environmentGeneration = 0;
  const RenderOptions referenceBase = o.reference ? *o.reference : viewReferenceOptions(o.render);
  // 2^16 by default: the device sums in float (the variance of the noise figure cancels beyond).
  const int referenceCap = o.referenceSpp > 0 ? o.referenceSpp : 1 << 16;
  struct Drawn {
    Camera camera;
    ShadingTerms terms = ShadingTerms::Both;
    float skyboxLod = 0.0f;
    int generation = -1;
    bool temporal = false;  // the real-time frame is the jitters' average (stillFrame)
  };
  Drawn traced, drawn;
  RenderResult reference, realTime, picture;
  bool pictureCurrent = false, referenceFailed = false;
  ViewMode pictured = ViewMode::RealTime;
  float picturedSplit = 0.5f;
  int batch = 1;  // samples per pixel added per frame: 1 to 16, sized to keep a frame interactive
  const auto recreate = [&] {
    vkDeviceWaitIdle(c.device);
    r.swapchain.destroy();
    createSwapchain(r, format);
  };
  while (!glfwWindowShouldClose(r.window) && (o.frames <= 0 || stats.frames < o.frames)) {
    glfwPollEvents();
    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(r.window, &fbWidth, &fbHeight);
    if (fbWidth == 0 || fbHeight == 0) {  // minimized
      glfwWaitEvents();
      continue;
    }
    check(vkWaitForFences(c.device, 1, &r.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    // Auto exposure: eased toward what the last frame's histogram asks for, over the time since.
    if (histogramRecorded && state.autoExposure)
      state.ev100 =
          adaptEv100(state.ev100, meteredEv100(r.histogram->read(), state.metering, state.ev100),
                     static_cast<float>(lastFrameMs / 1000.0), state.adaptationSpeed);
    histogramRecorded = false;
    // The last frame's passes on the device (a real-time frame's), for the panel.
    if (timedFrame) passTimes = r.renderer->passTimes();
    timedFrame = false;
    std::uint32_t imageIndex = 0;
    const VkResult acquired = vkAcquireNextImageKHR(c.device, r.swapchain.handle, UINT64_MAX,
                                                    r.acquired, VK_NULL_HANDLE, &imageIndex);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
      recreate();
      continue;
    }
    if (acquired != VK_SUBOPTIMAL_KHR) check(acquired, "vkAcquireNextImageKHR");
    vkResetFences(c.device, 1, &r.done);

    const VkExtent2D extent = r.swapchain.extent;
    const int width = static_cast<int>(extent.width), height = static_cast<int>(extent.height);
    renderer.prepare(width, height, samples);
    if (state.bloom && !r.bloom) r.bloom = std::make_unique<DeviceBloom>(*r.context);
    if (r.bloom) r.bloom->prepare(width, height);
    r.histogram->prepare(width, height);
    // The panel, from the controls as the events left them (it may change them in turn).
    PanelFigures figures;
    figures.frameMs = lastFrameMs;
    figures.device = c.info.name;
    figures.passes = passTimes;
    figures.deviceMemoryBytes = r.context->deviceMemoryBytes();
    figures.samples = samples;
    figures.timeOfDay = static_cast<bool>(o.timeOfDay);
    if (r.tracer) {
      figures.referenceSpp = r.tracer->samplesPerPixel();
      figures.referenceNoise = r.tracer->noise();
    }
    figures.canSaveSettings = static_cast<bool>(o.saveSettings);
    figures.canSaveLights = static_cast<bool>(o.saveLights);
    if (state.pickAt) {
      // The cursor's window point in framebuffer pixels, its center's ray into the CPU's scene
      // (the geometry is the window's; made on the first pick).
      int windowWidth = 0, windowHeight = 0;
      glfwGetWindowSize(r.window, &windowWidth, &windowHeight);
      const glm::vec2 scale(
          static_cast<float>(width) / static_cast<float>(std::max(windowWidth, 1)),
          static_cast<float>(height) / static_cast<float>(std::max(windowHeight, 1)));
      if (!pickTracer) pickTracer = std::make_unique<RayTracer>(scene);
      state.picked = pickedSurface(scene, *pickTracer, state.camera(width, height),
                                   glm::floor(*state.pickAt * scale) + 0.5f);
      std::string line;
      for (const std::string& fact : state.picked) line += (line.empty() ? "" : "; ") + fact;
      fmt::print(stderr, "ibl view: picked {}\n", line);
      state.pickAt.reset();
    }
    r.panel->build(state, figures);
    if (state.saveSettingsRequested || state.saveLightsRequested) {
      try {
        state.status =
            "saved " + (state.saveSettingsRequested ? o.saveSettings(state.settings(width, height))
                                                    : o.saveLights(state.lights));
      } catch (const Error& e) {
        state.status = e.what();
      }
      state.saveSettingsRequested = state.saveLightsRequested = false;
    }
    RenderOptions shading = o.render;
    shading.only = state.diffuse && state.specular ? ShadingTerms::Both
                   : state.diffuse                 ? ShadingTerms::Diffuse
                                                   : ShadingTerms::Specular;
    // A new environment: the sun moved (, and .), or a file or bake folder dropped on the window.
    std::optional<EnvironmentChange> change;
    const auto changeStart = Clock::now();
    if (state.timeStep != 0 && o.timeOfDay) {
      change = o.timeOfDay(state.timeStep, *r.context);
      // The lights as the panel left them, the sun (the last) moved.
      if (change && change->lights.size() == state.lights.size()) {
        const Light sun = change->lights.back();
        change->lights = state.lights;
        change->lights.back() = sun;
      }
    }
    if (!state.dropped.empty() && o.dropEnvironment) {
      try {
        change = o.dropEnvironment(state.dropped, *r.context);
        // The scene's own lights as the panel left them; the suns the new environment's.
        if (change && change->lights.size() == state.lights.size())
          for (std::size_t i = 0; i < state.lights.size(); ++i)
            if (change->lights[i].type != LightType::Sun) change->lights[i] = state.lights[i];
        state.status.clear();
      } catch (const Error& e) {
        state.status = e.what();
        fmt::print(stderr, "ibl view: {}\n", e.what());
      }
    }
    state.dropped.clear();
    {
      if (change) {
        renderer.setEnvironment(change->bake, change->options, change->lights);
        state.lights = change->lights;
        state.maxSkyboxLod = renderer.scene.skyboxMaxLod();
        // The reference is traced again, by a tracer of the new environment and lights.
        r.tracer.reset();
        environment = std::move(*change);
        changedScene = scene;
        changedScene.lights = environment->lights;
        referenceScene = &changedScene;
        referenceBake = &environment->bake;
        referenceBakeOptions = &environment->options;
        ++environmentGeneration;
        const double ms =
            std::chrono::duration<double, std::milli>(Clock::now() - changeStart).count();
        fmt::print(stderr, "ibl view: {}: new environment and bake in {:.0f} ms\n",
                   environment->label, ms);
        glfwSetWindowTitle(
            r.window, fmt::format("{} - {} ({:.0f} ms)", o.title, environment->label, ms).c_str());
        lastTitle = Clock::now();  // the frame-time title waits a moment
      }
    }
    state.timeStep = 0;
    if (state.lightsChanged) {  // moved, dimmed or recolored in the panel
      state.lightsChanged = false;
      renderer.setLights(state.lights);
      r.tracer.reset();
      changedScene = scene;
      changedScene.lights = state.lights;
      referenceScene = &changedScene;
      ++environmentGeneration;
    }

    // Outside the real-time view: the reference (made on first use), started over when what it
    // shows changed, a batch of samples further; the real-time frame when the view compares
    // with it; the picture uploaded when it changed.
    const Camera camera = state.camera(width, height);
    if (referenceFailed) state.view = ViewMode::RealTime;
    if (state.view != ViewMode::RealTime && !r.tracer) {
      try {
        r.tracer = std::make_unique<PathTracer>(*r.context, *referenceScene, *referenceBake,
                                                *referenceBakeOptions);
        traced.generation = -1;
      } catch (const Error& e) {
        // What the device reference cannot draw: said once, and the real-time view goes on.
        fmt::print(stderr, "ibl view: no reference view: {}\n", e.what());
        referenceFailed = true;
        state.view = ViewMode::RealTime;
      }
    }
    const ViewMode view = state.view;
    // A buffer view is the real-time view's: the comparisons with the reference show the shading.
    const BufferView buffer = view == ViewMode::RealTime ? state.buffer : BufferView::Shaded;
    r.renderer->setBufferView(buffer);
    r.renderer->setClay(view == ViewMode::RealTime && state.clay);
    // Temporal antialiasing in the real-time view; a still frame of it elsewhere (the frame
    // compared with the reference, a screenshot) is the jitters' average.
    r.renderer->setTemporalAntialiasing(view == ViewMode::RealTime && state.temporalAntialiasing,
                                        exposureFromEv100(state.ev100 - state.compensation));
    const auto stillFrame = [&] {
      return state.temporalAntialiasing
                 ? r.renderer->renderAccumulated(camera, shading, shared::kTemporalJitterPeriod,
                                                 state.skyboxLod)
                 : r.renderer->render(camera, shading, state.skyboxLod);
    };
    if (view != ViewMode::RealTime) {
      RenderOptions tracing = referenceBase;
      tracing.only = shading.only;
      if (traced.generation != environmentGeneration || traced.camera != camera ||
          traced.terms != tracing.only) {
        r.tracer->reset(camera, tracing);
        traced = {camera, tracing.only, 0.0f, environmentGeneration};
        batch = 1;
      }
      const int spp = r.tracer->samplesPerPixel();
      if (spp < referenceCap) {  // reset() leaves none: a new reference always gets a batch
        const auto start = Clock::now();
        r.tracer->accumulate(std::min(batch, referenceCap - spp));
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        if (ms < 12.0 && batch < 16)
          batch *= 2;
        else if (ms > 40.0 && batch > 1)
          batch /= 2;
        reference = r.tracer->result();
        pictureCurrent = false;
      }
      if (view != ViewMode::Reference &&
          (drawn.generation != environmentGeneration || drawn.camera != camera ||
           drawn.terms != shading.only || drawn.skyboxLod != state.skyboxLod ||
           drawn.temporal != state.temporalAntialiasing)) {
        realTime = stillFrame();
        drawn = {camera, shading.only, state.skyboxLod, environmentGeneration,
                 state.temporalAntialiasing};
        pictureCurrent = false;
      }
      if (!pictureCurrent || pictured != view || picturedSplit != state.split) {
        picture = composeView(view, realTime, reference, state.split);
        picturedSplit = state.split;
        uploadPicture(*r.context, r.shown, picture.color);
        pictureCurrent = true;
        pictured = view;
      }
    }

    if (state.screenshotRequested) {
      state.screenshotRequested = false;
      if (o.screenshot)
        o.screenshot(view == ViewMode::RealTime && buffer == BufferView::Shaded ? stillFrame()
                     : view == ViewMode::RealTime
                         ? r.renderer->render(camera, shading, state.skyboxLod)
                         : picture,
                     state.ev100 - state.compensation, state.toneMap, view, buffer);
    }
    // The difference view's colors and a buffer's are shown as they are: no bloom, exposure or
    // tone curve.
    const bool difference = view == ViewMode::Difference || buffer != BufferView::Shaded;
    const struct {
      float exposure;
      std::int32_t curve, encode;
    } push{difference ? 1.0f : exposureFromEv100(state.ev100 - state.compensation),
           difference || state.toneMap == ToneMap::None ? 0
           : state.toneMap == ToneMap::Aces             ? 1
                                                        : 2,
           encodesSrgb(format.format) ? 0 : 1};
    check(vkResetCommandBuffer(r.cmd, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(r.cmd, &begin), "vkBeginCommandBuffer");
    if (view == ViewMode::RealTime) {
      renderer.record(r.cmd, camera, shading, state.skyboxLod, o.volumeUpdate);
      timedFrame = true;
    }
    const DeviceImage& frame = view == ViewMode::RealTime ? renderer.output() : *r.shown;
    // Metered: what is shown, before bloom (the difference view's colors are no radiance).
    if (state.autoExposure && !difference) {
      r.histogram->record(r.cmd, frame);
      histogramRecorded = true;
      if (timedFrame) renderer.timer.mark(r.cmd, "histogram");
    }
    const bool bloomed = state.bloom && !difference;
    if (bloomed) {
      r.bloom->record(r.cmd, frame, state.ev100 - state.compensation, state.bloomStops);
      if (timedFrame) renderer.timer.mark(r.cmd, "bloom");
    }
    // The tone-mapping pass reads the frame, or its bloom.
    const VkDescriptorImageInfo hdrInfo{r.sampler,
                                        bloomed ? r.bloom->output().view() : frame.view(),
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const VkWriteDescriptorSet write = imageWrite(set, 0, &hdrInfo);
    vkUpdateDescriptorSets(c.device, 1, &write, 0, nullptr);
    VkRenderPassBeginInfo passBegin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    passBegin.renderPass = r.pass;
    passBegin.framebuffer = r.swapchain.framebuffers[imageIndex];
    passBegin.renderArea = {{0, 0}, extent};
    vkCmdBeginRenderPass(r.cmd, &passBegin, VK_SUBPASS_CONTENTS_INLINE);
    const VkViewport viewport{0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height),
                              0.0f, 1.0f};
    vkCmdSetViewport(r.cmd, 0, 1, &viewport);
    vkCmdSetScissor(r.cmd, 0, 1, &passBegin.renderArea);
    vkCmdBindPipeline(r.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.pipeline);
    vkCmdBindDescriptorSets(r.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.pipelineLayout, 0, 1, &set, 0,
                            nullptr);
    vkCmdPushConstants(r.cmd, r.pipelineLayout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push),
                       &push);
    vkCmdDraw(r.cmd, 3, 1, 0, 0);
    r.panel->record(r.cmd);
    vkCmdEndRenderPass(r.cmd);
    if (timedFrame) renderer.timer.mark(r.cmd, "tone map and panel");
    check(vkEndCommandBuffer(r.cmd), "vkEndCommandBuffer");
    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &r.acquired;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &r.cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &r.swapchain.rendered[imageIndex];
    check(vkQueueSubmit(c.queue, 1, &submit, r.done), "vkQueueSubmit");
    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &r.swapchain.rendered[imageIndex];
    present.swapchainCount = 1;
    present.pSwapchains = &r.swapchain.handle;
    present.pImageIndices = &imageIndex;
    const VkResult presented = vkQueuePresentKHR(c.queue, &present);
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR ||
        fbWidth != width || fbHeight != height)
      recreate();
    else
      check(presented, "vkQueuePresentKHR");

    const auto now = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last).count();
    last = now;
    lastFrameMs = ms;
    ++stats.frames;
    totalMs += ms;
    windowMs += ms;
    ++windowFrames;
    if (now - lastTitle > std::chrono::milliseconds(500) || stats.frames == 1) {
      const double mean = windowMs / windowFrames;
      // A buffer's name; outside the real-time view: the view, the reference's samples per pixel
      // and noise.
      const std::string shown =
          buffer != BufferView::Shaded ? fmt::format(" - buffer {}", bufferViewName(buffer))
          : view == ViewMode::RealTime || !r.tracer
              ? std::string()
              : fmt::format(" - {}: {} spp, reference noise {:.2f} %", viewModeName(view),
                            r.tracer->samplesPerPixel(), 100.0f * r.tracer->noise());
      glfwSetWindowTitle(
          r.window,
          fmt::format("{}{} - {:.2f} ms/frame ({:.0f} fps) - EV100 {:.1f} - skybox mip {:.1f} - "
                      "{} - {} - {}x MSAA - {}",
                      o.title, shown, mean, 1000.0 / mean, state.ev100 - state.compensation,
                      state.skyboxLod,
                      shading.only == ShadingTerms::Both      ? "diffuse + specular"
                      : shading.only == ShadingTerms::Diffuse ? "diffuse only"
                                                              : "specular only",
                      toneMapName(state.toneMap), samples, c.info.name)
              .c_str());
      lastTitle = now;
      windowMs = 0.0;
      windowFrames = 0;
    }
  }
  stats.meanFrameMs = stats.frames > 0 ? totalMs / stats.frames : 0.0;
  stats.view = state.view;
  stats.ev100 = state.ev100;
  if (r.tracer) {
    stats.referenceSpp = r.tracer->samplesPerPixel();
    stats.referenceNoise = r.tracer->noise();
  }
  return stats;
}

}  // namespace ibl::gpu
