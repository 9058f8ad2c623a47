#pragma once
// API: internal (may change without notice; the Vulkan back end of the command-line front end)
// The reference on the device: the path tracer of `ibl render --mode reference` (next-event
// estimation of every light, the emissive triangles and the environment, multiple importance
// sampling, Russian roulette, the same BRDF, sheen and multiple-scattering model) as a compute
// shader (shaders/render/path_trace.comp) over the scene's triangles in a bounding volume
// hierarchy built on the host by Embree's generic builder (src/gpu/bvh.hpp) and traversed in
// the shader (ibl/shared/bvh.h). The sampling and evaluation code is the CPU's: the shared
// headers ibl/shared/path_sampler.h, light_sampling.h, path_brdf.h and microfacet_walk.h.
// Runs on any Vulkan 1.1 device, Mesa's software device (lavapipe) included.
#include <functional>
#include <memory>

#include "ibl/bake/bake.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/render/scene.hpp"

namespace ibl::gpu {

// A progressive reference: samples are added to a per-pixel accumulation on the device, batch
// after batch, for as long as the camera and the options stay the same (the viewer's
// reference mode); reset() starts over.
class PathTracer {
 public:
  // Uploads the scene (its BVH, materials, textures, lights and emissive triangles) and the
  // environment the reference reads (the bake's source cube, level 0). `scene` and `bake` are
  // copied to the device and need not outlive the tracer. Throws Error("render: ...") for what
  // the device reference cannot draw (the same checks as renderScene).
  PathTracer(Context& context, const Scene& scene, const BakeResult& bake,
             const BakeOptions& bakeOptions);
  ~PathTracer();
  PathTracer(const PathTracer&) = delete;
  PathTracer& operator=(const PathTracer&) = delete;

  // Clears the accumulation and sets the view and the options (options.mode is taken as
  // RenderMode::Reference; noiseThreshold is ignored; options.spp == 1 alone traces each pixel's
  // center, as renderScene does for one sample: a progressive view passes 0).
  void reset(const Camera& camera, const RenderOptions& options);
  // Adds `samples` samples to every pixel: sample indices samplesPerPixel() .. + samples - 1 of
  // each pixel's low-discrepancy sequence, the numbers the CPU reference draws for the same
  // seed, pixel and index.
  void accumulate(int samples);
  int samplesPerPixel() const;  // accumulated since the last reset

  // The mean so far: linear radiance and coverage, as renderScene returns them (samples: the
  // total over all pixels; milliseconds: the device time spent since reset()).
  RenderResult result() const;
  // Per pixel, the variance of one sample's luminance (for the noise of the mean: / spp).
  std::vector<float> luminanceVariance() const;
  // How long the constructor waited for the driver to compile the shader (milliseconds).
  double preparationMilliseconds() const;
  // The estimated relative noise of the mean image: sqrt(mean variance of the pixels' means) /
  // mean luminance, over the covered pixels (0 before the first sample).
  float noise() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// renderScene(scene, camera, bake, bakeOptions, options) in RenderMode::Reference, on the
// device: the same options (spp, seed, bounces, terms, lights, ...) and result. Not supported:
// options.noiseThreshold (adaptive stopping) and options.aoRays (split sum only) are ignored.
RenderResult renderReference(Context& context, const Scene& scene, const Camera& camera,
                             const BakeResult& bake, const BakeOptions& bakeOptions,
                             const RenderOptions& options,
                             const std::function<void(float)>& progress = {});

}  // namespace ibl::gpu
