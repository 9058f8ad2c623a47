// Vulkan compute: instance, device, host-visible storage buffers, cached pipelines, dispatch.
#include <cstring>
#include <map>
#include <mutex>

#include <fmt/format.h>
#include <vulkan/vulkan.h>

#include "gpu/compute.hpp"
#include "gpu/spirv.hpp"
#include "ibl/error.hpp"
#include "ibl/gpu.hpp"

namespace ibl::gpu {

namespace {

void check(VkResult r, const char* what) {
  if (r != VK_SUCCESS)
    fail("vulkan", fmt::format("{} failed (VkResult {})", what, static_cast<int>(r)));
}

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

int computeQueueFamily(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (std::uint32_t i = 0; i < count; ++i)
    if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) return static_cast<int>(i);
  return -1;
}

VkInstance createInstance() {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "ibl";
  app.apiVersion = VK_API_VERSION_1_1;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
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

struct Context::Impl {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t family = 0;
  VkCommandPool pool = VK_NULL_HANDLE;
  DeviceInfo info;
  struct Pipeline {
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
  };
  std::map<std::string, Pipeline, std::less<>> pipelines;
  std::mutex mutex;  // the queue, command pool and pipeline cache are used by one thread at a time

  ~Impl() {
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
    if (instance) vkDestroyInstance(instance, nullptr);
  }

  std::uint32_t memoryType(std::uint32_t bits, VkMemoryPropertyFlags flags) const {
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(physical, &props);
    for (std::uint32_t i = 0; i < props.memoryTypeCount; ++i)
      if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) return i;
    fail("vulkan", "no host-visible memory type for storage buffers");
  }

  const Pipeline& pipeline(std::string_view name, std::uint32_t bindings, std::uint32_t pushBytes) {
    const auto found = pipelines.find(name);
    if (found != pipelines.end()) return found->second;
    const auto code = spirvFor(name);
    if (code.empty()) fail("vulkan", fmt::format("no shader named {}", name));
    Pipeline p;
    VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    moduleInfo.codeSize = code.size_bytes();
    moduleInfo.pCode = code.data();
    check(vkCreateShaderModule(device, &moduleInfo, nullptr, &p.module), "vkCreateShaderModule");
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
    check(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &p.layout),
          "vkCreatePipelineLayout");
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
    return pipelines.emplace(std::string(name), p).first->second;
  }
};

std::vector<DeviceInfo> listDevices() {
  std::vector<DeviceInfo> out;
  VkInstance instance = createInstance();
  if (!instance) return out;
  for (VkPhysicalDevice d : physicalDevices(instance))
    if (computeQueueFamily(d) >= 0) out.push_back(describe(d));
  vkDestroyInstance(instance, nullptr);
  return out;
}

Context::Context(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Context::~Context() = default;
const DeviceInfo& Context::device() const {
  return impl_->info;
}

std::unique_ptr<Context> Context::create() {
  auto impl = std::make_unique<Impl>();
  impl->instance = createInstance();
  if (!impl->instance)
    fail("vulkan",
         "no Vulkan loader or driver (install mesa-vulkan-drivers for the software device)");
  // Prefer a discrete GPU, then an integrated one, then any device with a compute queue.
  int best = -1;
  for (VkPhysicalDevice d : physicalDevices(impl->instance)) {
    if (computeQueueFamily(d) < 0) continue;
    const std::string type = describe(d).type;
    const int rank = type == "discrete" ? 3 : type == "integrated" ? 2 : 1;
    if (rank > best) {
      best = rank;
      impl->physical = d;
    }
  }
  if (!impl->physical) fail("vulkan", "no Vulkan device with a compute queue");
  impl->info = describe(impl->physical);
  impl->family = static_cast<std::uint32_t>(computeQueueFamily(impl->physical));
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = impl->family;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  check(vkCreateDevice(impl->physical, &deviceInfo, nullptr, &impl->device), "vkCreateDevice");
  vkGetDeviceQueue(impl->device, impl->family, 0, &impl->queue);
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.queueFamilyIndex = impl->family;
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  check(vkCreateCommandPool(impl->device, &poolInfo, nullptr, &impl->pool), "vkCreateCommandPool");
  return std::unique_ptr<Context>(new Context(std::move(impl)));
}

// ---- compute.hpp ----

Buffer::Buffer(Context& context, std::size_t bytes) : context_(&context), size_(bytes) {
  auto& c = context.impl();
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = std::max<std::size_t>(bytes, 16);
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer;
  check(vkCreateBuffer(c.device, &info, nullptr, &buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(c.device, buffer, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex =
      c.memoryType(req.memoryTypeBits,
                   VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceMemory memory;
  if (vkAllocateMemory(c.device, &alloc, nullptr, &memory) != VK_SUCCESS) {
    vkDestroyBuffer(c.device, buffer, nullptr);
    fail("vulkan", fmt::format("cannot allocate {} bytes", bytes));
  }
  vkBindBufferMemory(c.device, buffer, memory, 0);
  vkMapMemory(c.device, memory, 0, VK_WHOLE_SIZE, 0, &mapped_);
  buffer_ = buffer;
  memory_ = memory;
}

Buffer::~Buffer() {
  if (!buffer_) return;  // moved from
  auto& c = context_->impl();
  vkUnmapMemory(c.device, static_cast<VkDeviceMemory>(memory_));
  vkDestroyBuffer(c.device, static_cast<VkBuffer>(buffer_), nullptr);
  vkFreeMemory(c.device, static_cast<VkDeviceMemory>(memory_), nullptr);
}

void dispatch(Context& context, std::string_view shader, std::initializer_list<Buffer*> buffers,
              std::span<const std::uint8_t> pushConstants, std::uint32_t groupsX,
              std::uint32_t groupsY, std::uint32_t groupsZ) {
  auto& c = context.impl();
  const std::lock_guard lock(c.mutex);
  const auto& p = c.pipeline(shader, static_cast<std::uint32_t>(buffers.size()),
                             static_cast<std::uint32_t>(pushConstants.size()));
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                            static_cast<std::uint32_t>(buffers.size())};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &size;
  VkDescriptorPool pool;
  check(vkCreateDescriptorPool(c.device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo setAlloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  setAlloc.descriptorPool = pool;
  setAlloc.descriptorSetCount = 1;
  setAlloc.pSetLayouts = &p.setLayout;
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

  VkCommandBufferAllocateInfo cmdAlloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cmdAlloc.commandPool = c.pool;
  cmdAlloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cmdAlloc.commandBufferCount = 1;
  VkCommandBuffer cmd;
  check(vkAllocateCommandBuffers(c.device, &cmdAlloc, &cmd), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd, &begin);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &set, 0, nullptr);
  if (!pushConstants.empty())
    vkCmdPushConstants(cmd, p.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0,
                       static_cast<std::uint32_t>(pushConstants.size()), pushConstants.data());
  vkCmdDispatch(cmd, groupsX, groupsY, groupsZ);
  // Make the shader's writes visible to the host's reads of the mapped memory.
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                       &barrier, 0, nullptr, 0, nullptr);
  vkEndCommandBuffer(cmd);
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  check(vkCreateFence(c.device, &fenceInfo, nullptr, &fence), "vkCreateFence");
  const VkResult submitted = vkQueueSubmit(c.queue, 1, &submit, fence);
  const VkResult waited = submitted == VK_SUCCESS
                              ? vkWaitForFences(c.device, 1, &fence, VK_TRUE, UINT64_MAX)
                              : submitted;
  vkDestroyFence(c.device, fence, nullptr);
  vkFreeCommandBuffers(c.device, c.pool, 1, &cmd);
  vkDestroyDescriptorPool(c.device, pool, nullptr);
  check(submitted, "vkQueueSubmit");
  check(waited, "vkWaitForFences");
}

}  // namespace ibl::gpu
