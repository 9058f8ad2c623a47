#pragma once
// Internal: the irradiance volume on the viewer's device (view/frame.glsl's VolumeIrradiance,
// VolumeDistance and VolumeProbes, read by view/volume.glsl): its two atlases as 2D textures read
// bilinearly and clamped to the edge, and its probes' relocation records; 1 x 1 stand-ins
// without a volume.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <vulkan/vulkan.h>

#include "ibl/gpu/compute.hpp"
#include "ibl/render/irradiance_volume.hpp"

namespace ibl::gpu {

class Buffer;
class DeviceImage;
class FrameSet;
struct FrameState;

// The atlases' format on `context`'s device: RGBA32F where the device filters it linearly, else
// RGBA16F (which Vulkan requires every device to filter).
VkFormat volumeAtlasFormat(Context& context);

// An atlas's texels as `format` (RGBA32F or RGBA16F) holds them, row by row, A 1; RGBA16F's
// values are rounded to the nearest half and clamped to the largest one (65504).
std::vector<std::uint8_t> volumeAtlasTexels(const Image& atlas, VkFormat format);

class VolumeUpload {
 public:
  // Uploads `volume` (null: none, the stand-ins) in `format` (volumeAtlasFormat) and points the
  // frame set's bindings at it. Throws Error when an atlas is larger than the device's largest
  // 2D image.
  VolumeUpload(Context& context, FrameSet& frame, const IrradianceVolume* volume, VkFormat format);
  ~VolumeUpload();
  VolumeUpload(const VolumeUpload&) = delete;
  VolumeUpload& operator=(const VolumeUpload&) = delete;

  // Sets the volume's part of `state` (its grid, or none).
  void describe(FrameState& state) const;

  // What the frame set points at (VolumeUpdate rewrites the atlases).
  const DeviceImage& irradiance() const { return *irradiance_; }
  const DeviceImage& distance() const { return *distance_; }
  const Buffer& probes() const { return *probes_; }
  VkFormat format() const { return format_; }

 private:
  VkFormat format_;
  std::unique_ptr<DeviceImage> irradiance_, distance_;
  std::unique_ptr<Buffer> probes_;
  std::optional<shared::VolumeGrid> grid_;
};

}  // namespace ibl::gpu
