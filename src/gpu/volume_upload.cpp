// The irradiance volume on the viewer's device (volume_upload.hpp).
#include "gpu/volume_upload.hpp"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>
#include <glm/gtc/packing.hpp>

#include "gpu/buffers.hpp"
#include "gpu/frame_layout.hpp"
#include "gpu/frame_set.hpp"
#include "gpu/vulkan.hpp"
#include "ibl/core/error.hpp"

namespace ibl::gpu {

namespace {

std::size_t texelBytes(VkFormat format) {
  return format == VK_FORMAT_R16G16B16A16_SFLOAT ? 4 * sizeof(std::uint16_t) : 4 * sizeof(float);
}

// An atlas (or a 1 x 1 zero stand-in: null) on the device; Error when the device's 2D images
// are smaller.
std::unique_ptr<DeviceImage> uploadAtlas(Context& context, const Image* atlas, VkFormat format,
                                         const char* name) {
  const Image standIn(1, 1);
  const Image& texels = atlas ? *atlas : standIn;
  const std::uint32_t largest = context.impl().limits.maxImageDimension2D;
  if (static_cast<std::uint32_t>(std::max(texels.width, texels.height)) > largest)
    fail("--volume",
         fmt::format("the volume's {} atlas is {}x{} texels; {} allows {} a side "
                     "(capture a volume with fewer probes or smaller tiles)",
                     name, texels.width, texels.height, context.device().name, largest));
  DeviceImage::Description d;
  d.format = format;
  d.width = static_cast<std::uint32_t>(texels.width);
  d.height = static_cast<std::uint32_t>(texels.height);
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  auto image = std::make_unique<DeviceImage>(context, d);
  uploadImage(context, *image, volumeAtlasTexels(texels, format), texelBytes(format));
  return image;
}

}  // namespace

VkFormat volumeAtlasFormat(Context& context) {
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(context.impl().physical, VK_FORMAT_R32G32B32A32_SFLOAT,
                                      &props);
  const bool filtered =
      (props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
  return filtered ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
}

std::vector<std::uint8_t> volumeAtlasTexels(const Image& atlas, VkFormat format) {
  std::vector<std::uint8_t> out(atlas.pixels.size() * texelBytes(format));
  std::uint8_t* at = out.data();
  for (const glm::vec3& p : atlas.pixels) {
    const glm::vec4 texel(p, 1.0f);
    if (format == VK_FORMAT_R16G16B16A16_SFLOAT) {
      const float largestHalf = 65504.0f;
      for (int c = 0; c < 4; ++c) {
        const std::uint16_t h = glm::packHalf1x16(std::clamp(texel[c], -largestHalf, largestHalf));
        std::memcpy(at + c * sizeof(h), &h, sizeof(h));
      }
    } else {
      std::memcpy(at, &texel, sizeof(texel));
    }
    at += texelBytes(format);
  }
  return out;
}

VolumeUpload::VolumeUpload(Context& context, FrameSet& frame, const IrradianceVolume* volume,
                           VkFormat format)
    : format_(format) {
  irradiance_ = uploadAtlas(context, volume ? &volume->irradiance : nullptr, format, "irradiance");
  distance_ = uploadAtlas(context, volume ? &volume->distance : nullptr, format, "distance");
  // One record per probe (a buffer is never empty: one zero record without a volume).
  const std::vector<glm::vec4> records =
      volume ? relocationRecords(*volume) : std::vector<glm::vec4>(1, glm::vec4(0.0f));
  const std::size_t bytes = records.size() * sizeof(glm::vec4);
  probes_ = std::make_unique<Buffer>(context, bytes, BufferMemory::Host);
  std::memcpy(probes_->mapped(), records.data(), bytes);
  if (volume) grid_ = volume->grid;
  frame.writeImage(FrameBinding::VolumeIrradiance, frame.lutSampler(), irradiance_->view());
  frame.writeImage(FrameBinding::VolumeDistance, frame.lutSampler(), distance_->view());
  frame.writeBuffer(FrameBinding::VolumeProbes, *probes_);
}

VolumeUpload::~VolumeUpload() = default;

void VolumeUpload::describe(FrameState& state) const {
  state.volume = grid_;
}

}  // namespace ibl::gpu
