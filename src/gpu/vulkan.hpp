#pragma once
// Internal: the Vulkan objects behind gpu::Context and the small helpers the compute stages and
// the rasterizer share (checked calls, one-shot submissions, device images, barriers).
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include <vulkan/vulkan.h>

#include "ibl/gpu/compute.hpp"

namespace ibl::gpu {

// What a VkResult means, in words: "out of device memory (VK_ERROR_OUT_OF_DEVICE_MEMORY)".
std::string describe(VkResult r);

// Throws Error("vulkan: <what>: <describe(r)>") unless r is VK_SUCCESS.
void check(VkResult r, const char* what);

struct Context::Impl {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t family = 0;
  bool graphics = false;  // the queue also does graphics
  VkCommandPool pool = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;  // with IBL_VULKAN_VALIDATION
  VkPhysicalDeviceLimits limits{};
  bool mappableDeviceMemory = false;  // device-local memory the host can map (no staging)
  bool imageCubeArray = false;        // cube map arrays are enabled (the viewer's probes)
  DeviceInfo info;
  // Bytes of device memory the context's buffers and images hold now (Buffer, DeviceImage).
  std::atomic<std::uint64_t> deviceMemoryBytes{0};
  struct Pipeline {
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
  };
  std::map<std::string, Pipeline, std::less<>> pipelines;
  std::mutex mutex;  // the queue, command pool and pipeline cache are used by one thread at a time

  ~Impl();
  std::uint32_t memoryType(std::uint32_t bits, VkMemoryPropertyFlags flags) const;
  // A module of the embedded SPIR-V named `name` (the caller destroys it).
  VkShaderModule shaderModule(std::string_view name) const;
  // The compute pipeline of shader `name` with `bindings` storage buffers (cached).
  const Pipeline& computePipeline(std::string_view name, std::uint32_t bindings,
                                  std::uint32_t pushBytes);
  // Fills `p` step by step (the caller frees what exists if it throws).
  void createComputePipeline(Pipeline& p, std::string_view name, std::uint32_t bindings,
                             std::uint32_t pushBytes);
  // Records a command buffer with `record`, submits it and waits for it. Takes the mutex.
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record);
};

// Owns one Vulkan object of a device and destroys it with `destroy` (vkDestroyPipeline, ...) when
// it goes; moved, never copied. Converts to the handle (VK_NULL_HANDLE when empty), so that it
// is passed to Vulkan as it is.
template <typename T, void (*destroy)(VkDevice, T, const VkAllocationCallbacks*)>
class Unique {
 public:
  Unique() = default;
  // device: the object's device; handle: the object, now owned (VK_NULL_HANDLE: none).
  Unique(VkDevice device, T handle) : device_(device), handle_(handle) {}
  Unique(Unique&& other) noexcept
      : device_(other.device_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  Unique& operator=(Unique&& other) noexcept {
    if (this != &other) {
      reset();
      device_ = other.device_;
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }
  Unique(const Unique&) = delete;
  Unique& operator=(const Unique&) = delete;
  ~Unique() { reset(); }

  // Destroys the object now, if there is one.
  void reset() {
    if (handle_ != VK_NULL_HANDLE) destroy(device_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }
  T get() const { return handle_; }
  operator T() const { return handle_; }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  T handle_ = VK_NULL_HANDLE;
};
using UniquePipeline = Unique<VkPipeline, vkDestroyPipeline>;
using UniquePipelineLayout = Unique<VkPipelineLayout, vkDestroyPipelineLayout>;
using UniqueRenderPass = Unique<VkRenderPass, vkDestroyRenderPass>;
using UniqueFramebuffer = Unique<VkFramebuffer, vkDestroyFramebuffer>;
using UniqueShaderModule = Unique<VkShaderModule, vkDestroyShaderModule>;
using UniqueSampler = Unique<VkSampler, vkDestroySampler>;
using UniqueDescriptorSetLayout = Unique<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using UniqueDescriptorPool = Unique<VkDescriptorPool, vkDestroyDescriptorPool>;

// A device-local image and a view of all its levels and layers.
class DeviceImage {
 public:
  struct Description {
    VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT;
    std::uint32_t width = 1, height = 1, levels = 1, layers = 1;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    bool cube = false;
    bool cubeArray = false;  // with cube: viewed as an array of layers / 6 cubes
  };
  DeviceImage(Context& context, const Description& description);
  ~DeviceImage();
  DeviceImage(const DeviceImage&) = delete;
  DeviceImage& operator=(const DeviceImage&) = delete;

  VkImage image() const { return image_; }
  VkImageView view() const { return view_; }
  const Description& description() const { return description_; }

 private:
  Context::Impl* c_;
  Description description_;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  std::uint64_t allocated_ = 0;  // bytes of memory_ (Context::Impl::deviceMemoryBytes)
};

// A layout transition of every level and layer of `image`, ordered after the `from` stage and
// access masks and before the `to` ones.
void transitionImage(VkCommandBuffer cmd, const DeviceImage& image, VkImageLayout oldLayout,
                     VkImageLayout newLayout, VkPipelineStageFlags fromStage,
                     VkAccessFlags fromAccess, VkPipelineStageFlags toStage,
                     VkAccessFlags toAccess);
// The same for `levels` levels from `level` on.
void transitionImageLevels(VkCommandBuffer cmd, const DeviceImage& image, std::uint32_t level,
                           std::uint32_t levels, VkImageLayout oldLayout, VkImageLayout newLayout,
                           VkPipelineStageFlags fromStage, VkAccessFlags fromAccess,
                           VkPipelineStageFlags toStage, VkAccessFlags toAccess);

// Records the copy of a shader-readable color image's level 0, layer 0 (texels as the image's
// format holds them, row by row) into `readback`, a host-visible buffer of at least that size,
// which the host may read once the commands have run; the image ends shader-readable again.
void recordReadback(VkCommandBuffer cmd, const DeviceImage& image, VkBuffer readback);

// A graphics pipeline drawing triangles with both faces, no blending, dynamic viewport and
// scissor.
struct GraphicsPipelineDescription {
  VkShaderModule vertex = VK_NULL_HANDLE, fragment = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkRenderPass renderPass = VK_NULL_HANDLE;
  std::span<const VkVertexInputBindingDescription> bindings;  // empty: no vertex buffers
  std::span<const VkVertexInputAttributeDescription> attributes;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  bool depth = false;                  // depth test (less) and write
  bool depthWrite = true;              // with `depth`: false tests alone
  std::uint32_t colorAttachments = 1;  // written without blending (0: a depth-only pass)
  // Every color attachment's blending and write mask (null: written without blending).
  const VkPipelineColorBlendAttachmentState* blend = nullptr;
  // The fragment shader's specialization constants (null: their defaults).
  const VkSpecializationInfo* fragmentSpecialization = nullptr;
};
VkPipeline createGraphicsPipeline(VkDevice device, const GraphicsPipelineDescription& d);

// An attachment whose contents start undefined: loaded by `load`, stored by `store`, left in
// `finalLayout`; its stencil neither loaded nor stored.
inline VkAttachmentDescription attachmentDescription(
    VkFormat format, VkAttachmentLoadOp load, VkAttachmentStoreOp store, VkImageLayout finalLayout,
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT) {
  VkAttachmentDescription a{};
  a.format = format;
  a.samples = samples;
  a.loadOp = load;
  a.storeOp = store;
  a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  a.finalLayout = finalLayout;
  return a;
}

// A render pass of one subpass over `attachments`, with its dependencies on what comes before
// and after it.
VkRenderPass createRenderPass(VkDevice device, std::span<const VkAttachmentDescription> attachments,
                              const VkSubpassDescription& subpass,
                              std::span<const VkSubpassDependency> dependencies);

// A framebuffer of one layer over `views`, width x height, for `pass`.
VkFramebuffer createFramebuffer(VkDevice device, VkRenderPass pass,
                                std::span<const VkImageView> views, int width, int height);

// A descriptor write of one combined image sampler.
inline VkWriteDescriptorSet imageWrite(VkDescriptorSet set, std::uint32_t binding,
                                       const VkDescriptorImageInfo* info) {
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set;
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w.pImageInfo = info;
  return w;
}

// A descriptor write of one storage buffer.
inline VkWriteDescriptorSet storageBufferWrite(VkDescriptorSet set, std::uint32_t binding,
                                               const VkDescriptorBufferInfo* info) {
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set;
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  w.pBufferInfo = info;
  return w;
}

// Copies texels of `texelBytes` bytes each (levels one after another, layers one after another
// within a level, rows within a layer) into a sampled image and leaves it shader-readable.
void uploadImage(Context& context, const DeviceImage& image, std::span<const std::uint8_t> texels,
                 std::size_t texelBytes);

// Copies `frame` (RGBA32F, shader-readable, its size; written before by a render pass, a copy or a
// compute pass) into `buffer` from byte `offset`, after those writes and after compute or transfer
// writes to the buffer; leaves the frame shader-readable for the fragment shaders. The caller
// makes the copy's writes visible to what reads them.
void copyFrameToBuffer(VkCommandBuffer cmd, const DeviceImage& frame, VkBuffer buffer,
                       VkDeviceSize offset);

// Copies RGBA32F texels from `buffer`, from byte `offset` (row by row, written before by compute
// shaders or transfers), into `frame` (its size; what it held is discarded) and leaves it
// readable by fragment and compute shaders and by transfers.
void copyBufferToFrame(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset,
                       const DeviceImage& frame);

// An RGBA32F image for a frame of radiance, width x height: sampled, a transfer source and
// destination (what the bloom and the histogram copy from).
DeviceImage::Description radianceImage(int width, int height);
// Uploads `linear` (alpha 1) into `image` (radianceImage of its size) and leaves it
// shader-readable.
void uploadRadiance(Context& context, const DeviceImage& image, const Image& linear);

// A descriptor pool of `count` descriptors of `type` for `sets` sets, from which sets can be
// freed one by one. Throws Error("vulkan: ...").
VkDescriptorPool createDescriptorPool(VkDevice device, VkDescriptorType type, std::uint32_t count,
                                      std::uint32_t sets = 1);

}  // namespace ibl::gpu
