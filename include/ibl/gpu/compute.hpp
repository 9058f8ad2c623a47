#pragma once
// API: internal (may change without notice; the Vulkan back end of the command-line front end)
// The bake's stages as Vulkan compute shaders (shaders/{env,bake}/*.comp), sharing the math of the
// CPU path: the same formulas (ibl/shared/*.h, compiled as C++ and as GLSL) and the same Hammersley
// points. Runs on any Vulkan 1.1 device, Mesa's software device (lavapipe) included.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ibl/bake/prefilter.hpp"
#include "ibl/core/image.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/math/sh.hpp"

namespace ibl::gpu {

struct DeviceInfo {
  std::string name;
  std::string type;  // "discrete", "integrated", "virtual", "cpu", "other"
  std::uint32_t apiVersion = 0;
};

// Vulkan devices with a compute queue; empty when there is no Vulkan loader or device.
std::vector<DeviceInfo> listDevices();

struct ContextOptions {
  std::vector<std::string> instanceExtensions;  // e.g. the window system's surface extensions
  bool graphics = false;                        // a queue that also rasterizes (the viewer)
  bool swapchain = false;                       // VK_KHR_swapchain, to present to a window
  // Device-local buffers through staging copies even where the device lets the host map its
  // memory: the path of discrete GPUs, on any device (tests).
  bool stagingBuffers = false;
};

// With the environment variable IBL_VULKAN_VALIDATION=1, every context enables the Khronos
// validation layer (Debian: vulkan-validationlayers) and reports its warnings and errors on
// stderr; this counts them, over all contexts of the process (the GPU tests require 0).
std::size_t validationMessageCount();

// A Vulkan device, queue and the compiled pipelines. Prefers a discrete GPU, then an
// integrated one, then anything (lavapipe).
class Context {
 public:
  // Throws Error("vulkan: ...") when no device can be used.
  static std::unique_ptr<Context> create(const ContextOptions& options = {});
  ~Context();
  const DeviceInfo& device() const;
  // Bytes of device memory the context's buffers and images hold now.
  std::uint64_t deviceMemoryBytes() const;

  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  explicit Context(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// Where work that has both a CPU and a GPU path runs (the commands' --device): on the CPU, on a
// Vulkan device, or on a real GPU when there is one, else the CPU.
enum class ComputeDevice { Cpu, Gpu, Auto };
// "cpu", "gpu" or "auto" as a ComputeDevice; none for any other name.
std::optional<ComputeDevice> parseComputeDevice(std::string_view name);
// Whether `device` is a real GPU (discrete, integrated, virtual, other), not a software
// rasterizer (type "cpu", e.g. lavapipe), whose compute is slower than the CPU paths.
bool isHardwareDevice(const DeviceInfo& device);
// The Vulkan context for `choice`: none for Cpu; Context::create() for Gpu (throws
// Error("vulkan: ...") when no device can be used); for Auto, Context::create() when listDevices
// holds a real GPU (isHardwareDevice), else none (the software device is not picked).
std::unique_ptr<Context> openComputeDevice(ComputeDevice choice);

// GPU versions of buildMipChain (full chain), resampleToCube, prefilterGgx (both methods),
// integrateDfgLut, convolveIrradiance and projectSh9.
void buildMipChain(Context& context, CubeMap& cube);
// resampleToCube, for equirect and cube-map sources.
CubeMap resampleToCube(Context& context, const Environment& source, int size,
                       float rotateDegrees = 0.0f);
// prefilterGgx with either method: direct quadrature in rings (the passes on the device, their
// combination on the host, exactly as the CPU combines them) or filtered importance sampling.
CubeMap prefilterGgx(Context& context, const CubeMap& source, const PrefilterOptions& options,
                     std::vector<LevelMethod>* methods = nullptr, const ProgressFn& progress = {});
// One pass of the direct / ring prefilter (convolvePass in prefilter.hpp).
ConvolutionSums convolvePass(Context& context, const std::array<Image, kFaceCount>& sourceLevel,
                             int size, float roughness, PrefilterWeight weight, RadialWindow window,
                             float cosCap);
CubeMap prefilterGgxSampled(Context& context, const CubeMap& source,
                            const PrefilterOptions& options,
                            std::vector<LevelMethod>* methods = nullptr);
Image integrateDfgLut(Context& context, int width, int height, int samples);
CubeMap convolveIrradiance(Context& context, const CubeMap& source, int size, int sourceLevel);
Sh9 projectSh9(Context& context, const CubeMap& cube, int level);

// SkyModel(p).panorama(width, height, paintSun) computed on the device: shaders/sky/*.comp build
// the optical-depth, multiple-scattering, ground and sky-view tables with the CPU's per-point math
// (ibl/shared/sky.h) and marches, then the panorama; the sun's disk is painted on the host.
// Throws Error("sky: ...") for parameters or a size out of range, as the CPU path does.
Image skyPanorama(Context& context, const SkyParameters& p, int width, int height, bool paintSun);
// The sky's panorama on `device` when one is given (skyPanorama above), else on the CPU
// (SkyModel(p).panorama): linear Rec.709 in cd/m^2, equirect, width x height pixels, the sun's
// disk painted with `paintSun`. device: a context of openComputeDevice, or null. Throws as
// those.
Image skyPanoramaOn(Context* device, const SkyParameters& p, int width, int height, bool paintSun);

}  // namespace ibl::gpu
