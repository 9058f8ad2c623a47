// Vulkan: instance, device, host-visible buffers, device images, cached compute pipelines,
// one-shot submissions.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <fmt/format.h>

#include "gpu/buffers.hpp"
#include "gpu/spirv.hpp"
#include "gpu/vulkan.hpp"
#include "ibl/core/error.hpp"

namespace ibl::gpu {

std::string describe(VkResult r) {
  const auto words = [&]() -> std::pair<const char*, const char*> {
    switch (r) {
      case VK_ERROR_OUT_OF_HOST_MEMORY:
        return {"out of host memory", "VK_ERROR_OUT_OF_HOST_MEMORY"};
      case VK_ERROR_OUT_OF_DEVICE_MEMORY:
        return {"out of device memory", "VK_ERROR_OUT_OF_DEVICE_MEMORY"};
      case VK_ERROR_INITIALIZATION_FAILED:
        return {"the driver could not initialize", "VK_ERROR_INITIALIZATION_FAILED"};
      case VK_ERROR_DEVICE_LOST:
        return {"the device was lost (a driver crash or a time-out)", "VK_ERROR_DEVICE_LOST"};
      case VK_ERROR_MEMORY_MAP_FAILED:
        return {"the memory cannot be mapped", "VK_ERROR_MEMORY_MAP_FAILED"};
      case VK_ERROR_LAYER_NOT_PRESENT:
        return {"a requested layer is not installed", "VK_ERROR_LAYER_NOT_PRESENT"};
      case VK_ERROR_EXTENSION_NOT_PRESENT:
        return {"a required extension is missing", "VK_ERROR_EXTENSION_NOT_PRESENT"};
      case VK_ERROR_FEATURE_NOT_PRESENT:
        return {"a required feature is missing", "VK_ERROR_FEATURE_NOT_PRESENT"};
      case VK_ERROR_INCOMPATIBLE_DRIVER:
        return {"no compatible Vulkan driver", "VK_ERROR_INCOMPATIBLE_DRIVER"};
      case VK_ERROR_TOO_MANY_OBJECTS:
        return {"too many objects of one type", "VK_ERROR_TOO_MANY_OBJECTS"};
      case VK_ERROR_FORMAT_NOT_SUPPORTED:
        return {"the format is not supported", "VK_ERROR_FORMAT_NOT_SUPPORTED"};
      case VK_ERROR_FRAGMENTED_POOL:
        return {"a pool is fragmented", "VK_ERROR_FRAGMENTED_POOL"};
      case VK_ERROR_OUT_OF_POOL_MEMORY:
        return {"a descriptor pool is exhausted", "VK_ERROR_OUT_OF_POOL_MEMORY"};
      case VK_ERROR_SURFACE_LOST_KHR:
        return {"the window's surface was lost", "VK_ERROR_SURFACE_LOST_KHR"};
      case VK_ERROR_OUT_OF_DATE_KHR:
        return {"the window's swapchain is out of date", "VK_ERROR_OUT_OF_DATE_KHR"};
      case VK_TIMEOUT:
        return {"timed out", "VK_TIMEOUT"};
      default:
        return {nullptr, nullptr};
    }
  }();
  if (!words.first) return fmt::format("Vulkan error {}", static_cast<int>(r));
  return fmt::format("{} ({})", words.first, words.second);
}

void check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) fail("vulkan", fmt::format("{}: {}", what, describe(r)));
}

namespace {

std::string typeName(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "cpu";
    default:
      return "other";
  }
}

// The queue family to use: one that computes, preferably one that also rasterizes; -1 if none
// (or, when `graphics`, none that rasterizes).
int queueFamily(VkPhysicalDevice device, bool graphics) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  int computeOnly = -1;
  for (std::uint32_t i = 0; i < count; ++i) {
    const VkQueueFlags f = families[i].queueFlags;
    if ((f & VK_QUEUE_COMPUTE_BIT) && (f & VK_QUEUE_GRAPHICS_BIT)) return static_cast<int>(i);
    if ((f & VK_QUEUE_COMPUTE_BIT) && computeOnly < 0) computeOnly = static_cast<int>(i);
  }
  return graphics ? -1 : computeOnly;
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  std::uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

std::atomic<std::size_t> validationMessages{0};

// IBL_VULKAN_VALIDATION set to anything but "" or "0".
bool validationRequested() {
  const char* v = std::getenv("IBL_VULKAN_VALIDATION");
  return v && *v && std::strcmp(v, "0") != 0;
}

bool hasInstanceLayer(const char* name) {
  std::uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
    return std::strcmp(l.layerName, name) == 0;
  });
}

// Whether the instance layer `layer` provides the instance extension `name`.
bool layerHasExtension(const char* layer, const char* name) {
  std::uint32_t count = 0;
  vkEnumerateInstanceExtensionProperties(layer, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void*) {
  ++validationMessages;
  std::fprintf(stderr, "ibl: vulkan validation: %s\n", data->pMessage);
  return VK_FALSE;
}

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VkInstance createInstance(const std::vector<std::string>& extensions, bool validation = false) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "ibl";
  app.apiVersion = VK_API_VERSION_1_1;
  std::vector<const char*> names;
  for (const auto& e : extensions) names.push_back(e.c_str());
  // With the layer, its synchronization validation too, where the layer offers it: the hazards
  // between commands (a layout transition recorded before the reads it must wait for) that its
  // core checks leave out.
  const VkValidationFeatureEnableEXT enables[] = {
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  const bool synchronization =
      validation && layerHasExtension(kValidationLayer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  if (validation) names.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (synchronization) names.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledExtensionCount = static_cast<std::uint32_t>(names.size());
  info.ppEnabledExtensionNames = names.data();
  if (synchronization) info.pNext = &features;
  if (validation) {
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = &kValidationLayer;
  }
  VkInstance instance = VK_NULL_HANDLE;
  if (vkCreateInstance(&info, nullptr, &instance) != VK_SUCCESS) return VK_NULL_HANDLE;
  return instance;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  return devices;
}

DeviceInfo describe(VkPhysicalDevice device) {
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties(device, &p);
  return {p.deviceName, typeName(p.deviceType), p.apiVersion};
}

}  // namespace

Context::Impl::~Impl() {
  if (device) {
    vkDeviceWaitIdle(device);
    for (auto& [name, p] : pipelines) {
      vkDestroyPipeline(device, p.pipeline, nullptr);
      vkDestroyPipelineLayout(device, p.layout, nullptr);
      vkDestroyDescriptorSetLayout(device, p.setLayout, nullptr);
      vkDestroyShaderModule(device, p.module, nullptr);
    }
    vkDestroyCommandPool(device, pool, nullptr);
    vkDestroyDevice(device, nullptr);
  }
  if (messenger) {
    const auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance, messenger, nullptr);
  }
  if (instance) vkDestroyInstance(instance, nullptr);
}

std::uint32_t Context::Impl::memoryType(std::uint32_t bits, VkMemoryPropertyFlags flags) const {
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(physical, &props);
  for (std::uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) return i;
  fail("vulkan", fmt::format("no memory type with properties {:#x}", flags));
}

VkShaderModule Context::Impl::shaderModule(std::string_view name) const {
  const auto code = spirvFor(name);
  if (code.empty()) fail("vulkan", fmt::format("no shader named {}", name));
  VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  moduleInfo.codeSize = code.size_bytes();
  moduleInfo.pCode = code.data();
  VkShaderModule module;
  check(vkCreateShaderModule(device, &moduleInfo, nullptr, &module), "vkCreateShaderModule");
  return module;
}

const Context::Impl::Pipeline& Context::Impl::computePipeline(std::string_view name,
                                                              std::uint32_t bindings,
                                                              std::uint32_t pushBytes) {
  const auto found = pipelines.find(name);
  if (found != pipelines.end()) return found->second;
  Pipeline p;
  try {
    createComputePipeline(p, name, bindings, pushBytes);
  } catch (...) {  // free what was made (Vulkan ignores null handles)
    vkDestroyPipelineLayout(device, p.layout, nullptr);
    vkDestroyDescriptorSetLayout(device, p.setLayout, nullptr);
    vkDestroyShaderModule(device, p.module, nullptr);
    throw;
  }
  return pipelines.emplace(std::string(name), p).first->second;
}

void Context::Impl::createComputePipeline(Pipeline& p, std::string_view name,
                                          std::uint32_t bindings, std::uint32_t pushBytes) {
  p.module = shaderModule(name);
  std::vector<VkDescriptorSetLayoutBinding> b(bindings);
  for (std::uint32_t i = 0; i < bindings; ++i)
    b[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = bindings;
  setInfo.pBindings = b.data();
  check(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &p.setLayout),
        "vkCreateDescriptorSetLayout");
  VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &p.setLayout;
  layoutInfo.pushConstantRangeCount = pushBytes ? 1 : 0;
  layoutInfo.pPushConstantRanges = &push;
  check(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &p.layout), "vkCreatePipelineLayout");
  VkComputePipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  pipelineInfo.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                        nullptr,
                        0,
                        VK_SHADER_STAGE_COMPUTE_BIT,
                        p.module,
                        "main",
                        nullptr};
  pipelineInfo.layout = p.layout;
  check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &p.pipeline),
        "vkCreateComputePipelines");
}

void Context::Impl::submitAndWait(const std::function<void(VkCommandBuffer)>& record) {
  const std::lock_guard lock(mutex);
  VkCommandBufferAllocateInfo cmdAlloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cmdAlloc.commandPool = pool;
  cmdAlloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cmdAlloc.commandBufferCount = 1;
  VkCommandBuffer cmd;
  check(vkAllocateCommandBuffers(device, &cmdAlloc, &cmd), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  const VkResult begun = vkBeginCommandBuffer(cmd, &begin);
  if (begun == VK_SUCCESS) record(cmd);
  const VkResult ended = begun == VK_SUCCESS ? vkEndCommandBuffer(cmd) : begun;
  if (ended != VK_SUCCESS) {
    vkFreeCommandBuffers(device, pool, 1, &cmd);
    check(ended, "vkBeginCommandBuffer / vkEndCommandBuffer");
  }
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  check(vkCreateFence(device, &fenceInfo, nullptr, &fence), "vkCreateFence");
  const VkResult submitted = vkQueueSubmit(queue, 1, &submit, fence);
  const VkResult waited =
      submitted == VK_SUCCESS ? vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX) : submitted;
  vkDestroyFence(device, fence, nullptr);
  vkFreeCommandBuffers(device, pool, 1, &cmd);
  check(submitted, "vkQueueSubmit");
  check(waited, "vkWaitForFences");
}

std::size_t validationMessageCount() {
  return validationMessages.load();
}

std::vector<DeviceInfo> listDevices() {
  std::vector<DeviceInfo> out;
  VkInstance instance = createInstance({});
  if (!instance) return out;
  for (VkPhysicalDevice d : physicalDevices(instance))
    if (queueFamily(d, false) >= 0) out.push_back(describe(d));
  vkDestroyInstance(instance, nullptr);
  return out;
}

Context::Context(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Context::~Context() = default;
const DeviceInfo& Context::device() const {
  return impl_->info;
}

std::uint64_t Context::deviceMemoryBytes() const {
  return impl_->deviceMemoryBytes.load();
}

std::unique_ptr<Context> Context::create(const ContextOptions& options) {
  auto impl = std::make_unique<Impl>();
  const bool validation = validationRequested();
  if (validation && !hasInstanceLayer(kValidationLayer))
    fail("vulkan",
         "IBL_VULKAN_VALIDATION is set but the Khronos validation layer is not installed "
         "(Debian: vulkan-validationlayers)");
  impl->instance = createInstance(options.instanceExtensions, validation);
  if (!impl->instance)
    fail("vulkan",
         "no Vulkan loader or driver (install mesa-vulkan-drivers for the software device)");
  if (validation) {
    VkDebugUtilsMessengerCreateInfoEXT info{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    info.pfnUserCallback = onValidationMessage;
    const auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(impl->instance, "vkCreateDebugUtilsMessengerEXT"));
    if (!create) fail("vulkan", "VK_EXT_debug_utils is missing");
    check(create(impl->instance, &info, nullptr, &impl->messenger),
          "vkCreateDebugUtilsMessengerEXT");
  }
  // Prefer a discrete GPU, then an integrated one, then any device that can do the job.
  int best = -1;
  for (VkPhysicalDevice d : physicalDevices(impl->instance)) {
    if (queueFamily(d, options.graphics) < 0) continue;
    if (options.swapchain && !hasDeviceExtension(d, VK_KHR_SWAPCHAIN_EXTENSION_NAME)) continue;
    const std::string type = describe(d).type;
    const int rank = type == "discrete" ? 3 : type == "integrated" ? 2 : 1;
    if (rank > best) {
      best = rank;
      impl->physical = d;
    }
  }
  if (!impl->physical)
    fail("vulkan", options.graphics ? "no Vulkan device with a graphics and compute queue"
                                    : "no Vulkan device with a compute queue");
  impl->info = describe(impl->physical);
  {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(impl->physical, &props);
    impl->limits = props.limits;
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(impl->physical, &memory);
    constexpr VkMemoryPropertyFlags kMappable = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT |
                                                VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i)
      if ((memory.memoryTypes[i].propertyFlags & kMappable) == kMappable)
        impl->mappableDeviceMemory = !options.stagingBuffers;
  }
  impl->family = static_cast<std::uint32_t>(queueFamily(impl->physical, options.graphics));
  {
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(impl->physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(impl->physical, &count, families.data());
    impl->graphics = (families[impl->family].queueFlags & VK_QUEUE_GRAPHICS_BIT) != 0;
  }
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = impl->family;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  const char* swapchain = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.enabledExtensionCount = options.swapchain ? 1 : 0;
  deviceInfo.ppEnabledExtensionNames = &swapchain;
  // Cube map arrays where the device has them: the viewer's local probes are one array.
  VkPhysicalDeviceFeatures supported{}, enabled{};
  vkGetPhysicalDeviceFeatures(impl->physical, &supported);
  enabled.imageCubeArray = supported.imageCubeArray;
  impl->imageCubeArray = supported.imageCubeArray == VK_TRUE;
  deviceInfo.pEnabledFeatures = &enabled;
  check(vkCreateDevice(impl->physical, &deviceInfo, nullptr, &impl->device), "vkCreateDevice");
  vkGetDeviceQueue(impl->device, impl->family, 0, &impl->queue);
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.queueFamilyIndex = impl->family;
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  check(vkCreateCommandPool(impl->device, &poolInfo, nullptr, &impl->pool), "vkCreateCommandPool");
  return std::unique_ptr<Context>(new Context(std::move(impl)));
}

// ---- compute.hpp ----

Buffer::Buffer(Context& context, std::size_t bytes, BufferMemory memory)
    : context_(&context), size_(bytes) {
  auto& c = context.impl();
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = std::max<std::size_t>(bytes, 16);
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
               VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT |
               VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer;
  check(vkCreateBuffer(c.device, &info, nullptr, &buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(c.device, buffer, &req);
  const bool mapped = memory == BufferMemory::Host || c.mappableDeviceMemory;
  VkMemoryPropertyFlags flags =
      mapped ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT : 0;
  if (memory == BufferMemory::Device) flags |= VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  VkDeviceMemory deviceMemory = VK_NULL_HANDLE;
  VkResult r = VK_ERROR_OUT_OF_DEVICE_MEMORY;
  try {
    alloc.memoryTypeIndex = c.memoryType(req.memoryTypeBits, flags);
    r = vkAllocateMemory(c.device, &alloc, nullptr, &deviceMemory);
  } catch (...) {
    vkDestroyBuffer(c.device, buffer, nullptr);
    throw;
  }
  if (r == VK_SUCCESS) r = vkBindBufferMemory(c.device, buffer, deviceMemory, 0);
  if (r == VK_SUCCESS && mapped)
    r = vkMapMemory(c.device, deviceMemory, 0, VK_WHOLE_SIZE, 0, &mapped_);
  if (r != VK_SUCCESS) {
    vkDestroyBuffer(c.device, buffer, nullptr);
    vkFreeMemory(c.device, deviceMemory, nullptr);
    fail("vulkan", fmt::format("cannot allocate, bind or map a buffer of {} MB on {}: {}",
                               bytes >> 20, c.info.name, describe(r)));
  }
  buffer_ = buffer;
  memory_ = deviceMemory;
  allocated_ = req.size;
  c.deviceMemoryBytes += allocated_;
}

Buffer::~Buffer() {
  if (!buffer_) return;  // moved from
  auto& c = context_->impl();
  if (mapped_) vkUnmapMemory(c.device, static_cast<VkDeviceMemory>(memory_));
  vkDestroyBuffer(c.device, static_cast<VkBuffer>(buffer_), nullptr);
  vkFreeMemory(c.device, static_cast<VkDeviceMemory>(memory_), nullptr);
  c.deviceMemoryBytes -= allocated_;
}

void Buffer::upload(const void* data, std::size_t bytes) {
  if (bytes == 0) return;
  if (mapped_) {
    std::memcpy(mapped_, data, bytes);
    return;
  }
  Buffer staging(*context_, bytes, BufferMemory::Host);
  std::memcpy(staging.mapped_, data, bytes);
  context_->impl().submitAndWait([&](VkCommandBuffer cmd) {
    const VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, static_cast<VkBuffer>(staging.buffer_), static_cast<VkBuffer>(buffer_), 1,
                    &region);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0,
                         1, &barrier, 0, nullptr, 0, nullptr);
  });
}

void Buffer::download(void* data, std::size_t bytes) const {
  if (bytes == 0) return;
  if (mapped_) {
    std::memcpy(data, mapped_, bytes);
    return;
  }
  Buffer staging(*context_, bytes, BufferMemory::Host);
  context_->impl().submitAndWait([&](VkCommandBuffer cmd) {
    const VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, static_cast<VkBuffer>(buffer_), static_cast<VkBuffer>(staging.buffer_), 1,
                    &region);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                         &barrier, 0, nullptr, 0, nullptr);
  });
  std::memcpy(data, staging.mapped_, bytes);
}

void dispatch(Context& context, std::string_view shader, std::initializer_list<Buffer*> buffers,
              std::span<const std::uint8_t> pushConstants, std::uint32_t groupsX,
              std::uint32_t groupsY, std::uint32_t groupsZ) {
  auto& c = context.impl();
  // The device's limits, checked here rather than left to undefined behaviour.
  const std::uint32_t groups[3] = {groupsX, groupsY, groupsZ};
  for (int i = 0; i < 3; ++i)
    if (groups[i] > c.limits.maxComputeWorkGroupCount[i])
      fail("vulkan",
           fmt::format("{}: {} work groups along axis {} exceed the device's limit of {}; "
                       "use a smaller size",
                       shader, groups[i], i, c.limits.maxComputeWorkGroupCount[i]));
  for (const Buffer* b : buffers)
    if (b->size() > c.limits.maxStorageBufferRange)
      fail("vulkan", fmt::format("{}: a buffer of {} bytes exceeds the device's storage-buffer "
                                 "range of {} bytes; use a smaller size",
                                 shader, b->size(), c.limits.maxStorageBufferRange));
  if (pushConstants.size() > c.limits.maxPushConstantsSize)
    fail("vulkan", fmt::format("{}: {} bytes of push constants exceed the device's {}", shader,
                               pushConstants.size(), c.limits.maxPushConstantsSize));
  const Context::Impl::Pipeline* p;
  {
    const std::lock_guard lock(c.mutex);
    p = &c.computePipeline(shader, static_cast<std::uint32_t>(buffers.size()),
                           static_cast<std::uint32_t>(pushConstants.size()));
  }
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                            static_cast<std::uint32_t>(buffers.size())};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &size;
  VkDescriptorPool pool;
  check(vkCreateDescriptorPool(c.device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
  struct PoolGuard {
    VkDevice device;
    VkDescriptorPool pool;
    ~PoolGuard() { vkDestroyDescriptorPool(device, pool, nullptr); }
  } guard{c.device, pool};
  VkDescriptorSetAllocateInfo setAlloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  setAlloc.descriptorPool = pool;
  setAlloc.descriptorSetCount = 1;
  setAlloc.pSetLayouts = &p->setLayout;
  VkDescriptorSet set;
  check(vkAllocateDescriptorSets(c.device, &setAlloc, &set), "vkAllocateDescriptorSets");
  std::vector<VkDescriptorBufferInfo> infos;
  for (Buffer* b : buffers) infos.push_back({static_cast<VkBuffer>(b->handle()), 0, VK_WHOLE_SIZE});
  std::vector<VkWriteDescriptorSet> writes;
  for (std::uint32_t i = 0; i < infos.size(); ++i) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = i;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &infos[i];
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(c.device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
  c.submitAndWait([&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 1, &set, 0, nullptr);
    if (!pushConstants.empty())
      vkCmdPushConstants(cmd, p->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0,
                         static_cast<std::uint32_t>(pushConstants.size()), pushConstants.data());
    vkCmdDispatch(cmd, groupsX, groupsY, groupsZ);
    // Make the shader's writes visible to the host's reads of the mapped memory.
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0,
                         1, &barrier, 0, nullptr, 0, nullptr);
  });
}

// ---- vulkan.hpp ----

DeviceImage::DeviceImage(Context& context, const Description& d)
    : c_(&context.impl()), description_(d) {
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.flags = d.cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = d.format;
  info.extent = {d.width, d.height, 1};
  info.mipLevels = d.levels;
  info.arrayLayers = d.layers;
  info.samples = d.samples;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = d.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  const std::uint32_t largest =
      d.cube ? c_->limits.maxImageDimensionCube : c_->limits.maxImageDimension2D;
  if (d.width > largest || d.height > largest)
    fail("vulkan", fmt::format("a {}x{} {}image exceeds what {} allows ({} pixels a side); use a "
                               "smaller --size",
                               d.width, d.height, d.cube ? "cube " : "", c_->info.name, largest));
  check(vkCreateImage(c_->device, &info, nullptr, &image_), "vkCreateImage");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(c_->device, image_, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = c_->memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VkResult r = vkAllocateMemory(c_->device, &alloc, nullptr, &memory_);
  if (r == VK_SUCCESS) {
    r = vkBindImageMemory(c_->device, image_, memory_, 0);
    if (r != VK_SUCCESS) vkFreeMemory(c_->device, memory_, nullptr);
  }
  if (r != VK_SUCCESS) {
    vkDestroyImage(c_->device, image_, nullptr);
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(c_->physical, &memory);
    const VkDeviceSize heap =
        memory.memoryHeaps[memory.memoryTypes[alloc.memoryTypeIndex].heapIndex].size;
    fail("vulkan",
         fmt::format("cannot allocate a {}x{} image of {} MB on {} (a heap of {} MB): {}; use a "
                     "smaller --size",
                     d.width, d.height, req.size >> 20, c_->info.name, heap >> 20, describe(r)));
  }
  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = image_;
  viewInfo.viewType = !d.cube       ? VK_IMAGE_VIEW_TYPE_2D
                      : d.cubeArray ? VK_IMAGE_VIEW_TYPE_CUBE_ARRAY
                                    : VK_IMAGE_VIEW_TYPE_CUBE;
  viewInfo.format = d.format;
  viewInfo.subresourceRange = {d.aspect, 0, d.levels, 0, d.layers};
  r = vkCreateImageView(c_->device, &viewInfo, nullptr, &view_);
  if (r != VK_SUCCESS) {
    vkDestroyImage(c_->device, image_, nullptr);
    vkFreeMemory(c_->device, memory_, nullptr);
    check(r, "vkCreateImageView");
  }
  allocated_ = req.size;
  c_->deviceMemoryBytes += allocated_;
}

DeviceImage::~DeviceImage() {
  vkDestroyImageView(c_->device, view_, nullptr);
  vkDestroyImage(c_->device, image_, nullptr);
  vkFreeMemory(c_->device, memory_, nullptr);
  c_->deviceMemoryBytes -= allocated_;
}

void transitionImage(VkCommandBuffer cmd, const DeviceImage& image, VkImageLayout oldLayout,
                     VkImageLayout newLayout, VkPipelineStageFlags fromStage,
                     VkAccessFlags fromAccess, VkPipelineStageFlags toStage,
                     VkAccessFlags toAccess) {
  transitionImageLevels(cmd, image, 0, image.description().levels, oldLayout, newLayout, fromStage,
                        fromAccess, toStage, toAccess);
}

void transitionImageLevels(VkCommandBuffer cmd, const DeviceImage& image, std::uint32_t level,
                           std::uint32_t levels, VkImageLayout oldLayout, VkImageLayout newLayout,
                           VkPipelineStageFlags fromStage, VkAccessFlags fromAccess,
                           VkPipelineStageFlags toStage, VkAccessFlags toAccess) {
  const auto& d = image.description();
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = fromAccess;
  b.dstAccessMask = toAccess;
  b.oldLayout = oldLayout;
  b.newLayout = newLayout;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image.image();
  b.subresourceRange = {d.aspect, level, levels, 0, d.layers};
  vkCmdPipelineBarrier(cmd, fromStage, toStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

void recordReadback(VkCommandBuffer cmd, const DeviceImage& image, VkBuffer readback) {
  // The layout transition after the shaders that read the image (a read needs no availability,
  // only the wait).
  transitionImage(cmd, image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                      VK_PIPELINE_STAGE_TRANSFER_BIT,
                  0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {image.description().width, image.description().height, 1};
  vkCmdCopyImageToBuffer(cmd, image.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback, 1,
                         &region);
  transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                  VK_ACCESS_SHADER_READ_BIT);
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                       &barrier, 0, nullptr, 0, nullptr);
}

void copyFrameToBuffer(VkCommandBuffer cmd, const DeviceImage& frame, VkBuffer buffer,
                       VkDeviceSize offset) {
  transitionImage(cmd, frame, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT |
                      VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
  VkBufferImageCopy region{};
  region.bufferOffset = offset;
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {frame.description().width, frame.description().height, 1};
  vkCmdCopyImageToBuffer(cmd, frame.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1,
                         &region);
  transitionImage(cmd, frame, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                  VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

void copyBufferToFrame(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset,
                       const DeviceImage& frame) {
  VkMemoryBarrier written{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  written.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  written.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &written, 0, nullptr, 0, nullptr);
  transitionImage(cmd, frame, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                      VK_PIPELINE_STAGE_TRANSFER_BIT,
                  0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
  VkBufferImageCopy region{};
  region.bufferOffset = offset;
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {frame.description().width, frame.description().height, 1};
  vkCmdCopyBufferToImage(cmd, buffer, frame.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                         &region);
  transitionImage(cmd, frame, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                      VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

DeviceImage::Description radianceImage(int width, int height) {
  DeviceImage::Description d;
  d.width = static_cast<std::uint32_t>(width);
  d.height = static_cast<std::uint32_t>(height);
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
            VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  return d;
}

void uploadRadiance(Context& context, const DeviceImage& image, const Image& linear) {
  std::vector<glm::vec4> texels(linear.pixels.size());
  for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = glm::vec4(linear.pixels[i], 1.0f);
  uploadImage(
      context, image,
      {reinterpret_cast<const std::uint8_t*>(texels.data()), texels.size() * sizeof(glm::vec4)},
      sizeof(glm::vec4));
}

VkDescriptorPool createDescriptorPool(VkDevice device, VkDescriptorType type, std::uint32_t count,
                                      std::uint32_t sets) {
  const VkDescriptorPoolSize size{type, count};
  VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  info.maxSets = sets;
  info.poolSizeCount = 1;
  info.pPoolSizes = &size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  check(vkCreateDescriptorPool(device, &info, nullptr, &pool), "vkCreateDescriptorPool");
  return pool;
}

void uploadImage(Context& context, const DeviceImage& image, std::span<const std::uint8_t> texels,
                 std::size_t texelBytes) {
  const auto& d = image.description();
  Buffer staging(context, texels.size(), BufferMemory::Host);
  std::memcpy(staging.mapped(), texels.data(), texels.size());
  std::vector<VkBufferImageCopy> regions;
  VkDeviceSize offset = 0;
  for (std::uint32_t level = 0; level < d.levels; ++level) {
    const std::uint32_t w = std::max(d.width >> level, 1u), h = std::max(d.height >> level, 1u);
    VkBufferImageCopy r{};
    r.bufferOffset = offset;
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, d.layers};
    r.imageExtent = {w, h, 1};
    regions.push_back(r);
    offset += VkDeviceSize{w} * h * d.layers * texelBytes;
  }
  if (offset != texels.size()) fail("vulkan", "image upload of the wrong size");
  context.impl().submitAndWait([&](VkCommandBuffer cmd) {
    transitionImage(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdCopyBufferToImage(cmd, static_cast<VkBuffer>(staging.handle()), image.image(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           static_cast<std::uint32_t>(regions.size()), regions.data());
    transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                    VK_ACCESS_SHADER_READ_BIT);
  });
}

VkFramebuffer createFramebuffer(VkDevice device, VkRenderPass pass,
                                std::span<const VkImageView> views, int width, int height) {
  VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  info.renderPass = pass;
  info.attachmentCount = static_cast<std::uint32_t>(views.size());
  info.pAttachments = views.data();
  info.width = static_cast<std::uint32_t>(width);
  info.height = static_cast<std::uint32_t>(height);
  info.layers = 1;
  VkFramebuffer framebuffer;
  check(vkCreateFramebuffer(device, &info, nullptr, &framebuffer), "vkCreateFramebuffer");
  return framebuffer;
}

VkRenderPass createRenderPass(VkDevice device, std::span<const VkAttachmentDescription> attachments,
                              const VkSubpassDescription& subpass,
                              std::span<const VkSubpassDependency> dependencies) {
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = static_cast<std::uint32_t>(attachments.size());
  info.pAttachments = attachments.data();
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = static_cast<std::uint32_t>(dependencies.size());
  info.pDependencies = dependencies.data();
  VkRenderPass pass = VK_NULL_HANDLE;
  check(vkCreateRenderPass(device, &info, nullptr, &pass), "vkCreateRenderPass");
  return pass;
}

VkPipeline createGraphicsPipeline(VkDevice device, const GraphicsPipelineDescription& d) {
  const std::array<VkPipelineShaderStageCreateInfo, 2> stages{
      VkPipelineShaderStageCreateInfo{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr,
                                      0, VK_SHADER_STAGE_VERTEX_BIT, d.vertex, "main", nullptr},
      VkPipelineShaderStageCreateInfo{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr,
                                      0, VK_SHADER_STAGE_FRAGMENT_BIT, d.fragment, "main",
                                      d.fragmentSpecialization}};
  VkPipelineVertexInputStateCreateInfo input{
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  input.vertexBindingDescriptionCount = static_cast<std::uint32_t>(d.bindings.size());
  input.pVertexBindingDescriptions = d.bindings.data();
  input.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(d.attributes.size());
  input.pVertexAttributeDescriptions = d.attributes.data();
  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{
      VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = d.samples;
  VkPipelineDepthStencilStateCreateInfo depthState{
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depthState.depthTestEnable = d.depth ? VK_TRUE : VK_FALSE;
  depthState.depthWriteEnable = d.depth && d.depthWrite ? VK_TRUE : VK_FALSE;
  depthState.depthCompareOp = VK_COMPARE_OP_LESS;
  VkPipelineColorBlendAttachmentState blendAttachment{};
  blendAttachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                   VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  const std::vector<VkPipelineColorBlendAttachmentState> blendAttachments(
      d.colorAttachments, d.blend ? *d.blend : blendAttachment);
  VkPipelineColorBlendStateCreateInfo blend{
      VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = d.colorAttachments;
  blend.pAttachments = blendAttachments.data();
  const std::array<VkDynamicState, 2> dynamic{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamicState{
      VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamicState.dynamicStateCount = static_cast<std::uint32_t>(dynamic.size());
  dynamicState.pDynamicStates = dynamic.data();
  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = static_cast<std::uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depthState;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamicState;
  info.layout = d.layout;
  info.renderPass = d.renderPass;
  VkPipeline pipeline;
  check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
        "vkCreateGraphicsPipelines");
  return pipeline;
}

}  // namespace ibl::gpu
