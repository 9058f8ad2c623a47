// Where work with a CPU and a GPU path runs: the commands' --device, and the sky on either.
#include "ibl/env/sky.hpp"
#include "ibl/gpu/compute.hpp"

namespace ibl::gpu {

std::optional<ComputeDevice> parseComputeDevice(std::string_view name) {
  if (name == "cpu") return ComputeDevice::Cpu;
  if (name == "gpu") return ComputeDevice::Gpu;
  if (name == "auto") return ComputeDevice::Auto;
  return std::nullopt;
}

bool isHardwareDevice(const DeviceInfo& device) {
  return device.type != "cpu";
}

std::unique_ptr<Context> openComputeDevice(ComputeDevice choice) {
  if (choice == ComputeDevice::Cpu) return nullptr;
  if (choice == ComputeDevice::Auto) {
    bool realGpu = false;
    for (const auto& d : listDevices()) realGpu |= isHardwareDevice(d);
    if (!realGpu) return nullptr;
  }
  return Context::create();
}

Image skyPanoramaOn(Context* device, const SkyParameters& p, int width, int height, bool paintSun) {
  return device ? skyPanorama(*device, p, width, height, paintSun)
                : SkyModel(p).panorama(width, height, paintSun);
}

}  // namespace ibl::gpu
