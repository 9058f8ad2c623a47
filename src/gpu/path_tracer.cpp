// The reference on the device: the host side of shaders/render/path_trace.comp. The scene, the
// environment and the tables go up once into storage buffers; every accumulate() dispatches the
// shader over the image for a batch of samples, which add to the per-pixel sums on the device.
#include "ibl/gpu/path_tracer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iterator>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "gpu/buffers.hpp"
#include "gpu/scene_buffers.hpp"
#include "ibl/core/error.hpp"
#include "ibl/math/color.hpp"
#include "ibl/shared/charlie_table.h"
#include "render/path_tracer.hpp"

namespace ibl::gpu {

namespace {

enum Flag : int {
  kFlagVisibility = 1,
  kFlagEnvironmentLight = 2,
  kFlagBackgroundEnvironment = 4,
  kFlagCameraSeesEmitters = 8,
  kFlagCameraSeesSpecular = 16,
  kFlagCaptureMetalsAsDiffuse = 32,
  kFlagPixelCenter = 64,
  kFlagTransmits = 128,
};

}  // namespace

struct PathTracer::Impl {
  Context& context;
  SceneBuffers scene;
  std::unique_ptr<Buffer> parametersBuffer, texels, levels, tables, accumulation;
  SceneParameters parameters{};
  std::vector<float> tableHost;  // what `tables` holds
  std::size_t iesFloats = 0;     // at its end: the IES lights' tables
  int albedoVisibility = -1;     // the sheen visibility whose albedo tables `tables` holds
  bool transmits = false;        // some material transmits (hasTransmission)
  int width = 0, height = 0, spp = 0;
  double milliseconds = 0.0;
  double compileMilliseconds = 0.0;

  explicit Impl(Context& c) : context(c) {}
};

PathTracer::PathTracer(Context& context, const Scene& scene, const BakeResult& bake,
                       const BakeOptions& bakeOptions)
    : impl_(std::make_unique<Impl>(context)) {
  (void)bakeOptions;
  Impl& r = *impl_;
  if (bake.source.levels.empty()) fail("render", "the bake has no source cube");
  preparePathTracer();

  // The scene, then what the reference adds: the environment and its tables.
  r.scene = uploadSceneBuffers(context, scene);
  r.transmits = hasTransmission(scene);
  r.parameters.counts = r.scene.counts;
  r.parameters.offsets = r.scene.offsets;
  r.parameters.offsets2 = r.scene.offsets2;
  const std::vector<float>& iesTables = r.scene.iesTables;
  // The environment: level 0 of the source cube, its sampling tables, the albedo tables, the
  // Charlie table (the sheen's exact Lambda).
  const auto& level = bake.source.levels[0];
  const int n = level[0].width;
  r.parameters.counts.w = static_cast<std::uint32_t>(n);
  std::vector<glm::vec4> envTexels;
  envTexels.reserve(static_cast<std::size_t>(6) * n * n);
  for (const Image& face : level)
    for (const glm::vec3& p : face.pixels) envTexels.push_back(glm::vec4(p, 0.0f));
  r.texels = std::make_unique<Buffer>(Buffer::of(context, envTexels));
  r.levels = std::make_unique<Buffer>(
      Buffer::of(context, std::vector<glm::uvec2>{{static_cast<std::uint32_t>(n), 0u}}));
  const EnvironmentSampler environment(level);
  std::vector<float> tableData;
  for (double c : environment.rowCdf()) tableData.push_back(static_cast<float>(c));
  for (double c : environment.columnCdf()) tableData.push_back(static_cast<float>(c));
  // The albedo tables are those of the render's sheen visibility: both are uploaded by reset().
  tableData.resize(tableData.size() + 2 * shared::kAlbedoTableNodes * shared::kAlbedoTableNodes);
  tableData.insert(tableData.end(), std::begin(shared::kCharlieProjectedArea),
                   std::end(shared::kCharlieProjectedArea));
  r.iesFloats = iesTables.size();
  tableData.insert(tableData.end(), iesTables.begin(), iesTables.end());
  r.tables = std::make_unique<Buffer>(Buffer::of(context, tableData));
  r.tableHost = std::move(tableData);
  r.parametersBuffer = std::make_unique<Buffer>(context, sizeof(SceneParameters));
  // The pipeline is compiled here, by an empty dispatch, so that the first batch's time is its
  // own (a driver without a warm shader cache takes seconds: lavapipe about 40).
  const auto start = std::chrono::steady_clock::now();
  r.accumulation = std::make_unique<Buffer>(context, 2 * sizeof(glm::vec4));
  r.parameters.image = {1u, 1u, 0u, 0u};
  r.parametersBuffer->upload(&r.parameters, sizeof(SceneParameters));
  dispatch(context, "path_trace",
           {r.parametersBuffer.get(), r.scene.nodes.get(), r.scene.triangles.get(),
            r.scene.sceneData.get(), r.scene.words.get(), r.texels.get(), r.levels.get(),
            r.tables.get(), r.accumulation.get()},
           {}, 1, 1);
  r.compileMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double PathTracer::preparationMilliseconds() const {
  return impl_->compileMilliseconds;
}

PathTracer::~PathTracer() = default;

void PathTracer::reset(const Camera& camera, const RenderOptions& o) {
  Impl& r = *impl_;
  if (camera.width < 1 || camera.height < 1)
    fail("render", fmt::format("an image of {} x {} pixels is empty", camera.width, camera.height));
  SceneParameters& p = r.parameters;
  const CameraFrame f = camera.frame();
  const float aspect = static_cast<float>(camera.width) / static_cast<float>(camera.height);
  if (camera.perspective) {
    const float t = std::tan(0.5f * glm::radians(camera.yfovDegrees));
    p.cameraPosition = glm::vec4(camera.from, 1.0f);
    p.cameraRight = glm::vec4(f.right * (aspect * t), 0.0f);
    p.cameraUp = glm::vec4(f.up * t, 0.0f);
  } else {
    const float halfWidth = 0.5f * camera.orthoWidth, halfHeight = halfWidth / aspect;
    p.cameraPosition = glm::vec4(camera.from, 0.0f);
    p.cameraRight = glm::vec4(f.right * halfWidth, 0.0f);
    p.cameraUp = glm::vec4(f.up * halfHeight, 0.0f);
  }
  p.cameraForward = glm::vec4(f.forward, 0.0f);
  p.background = glm::vec4(o.backgroundColor, 0.0f);
  p.image = {static_cast<std::uint32_t>(camera.width), static_cast<std::uint32_t>(camera.height),
             0u, 0u};
  const shared::PathShading s = pathShading(o);
  p.shading = {s.diffuseModel, s.multipleScattering, s.specularMicroOcclusion ? 1 : 0,
               s.sheenVisibility};
  int flags = 0;
  if (o.shadows || o.bounces > 0) flags |= kFlagVisibility;
  if (o.environmentLight) flags |= kFlagEnvironmentLight;
  if (o.backgroundEnvironment) flags |= kFlagBackgroundEnvironment;
  if (o.cameraSeesEmitters) flags |= kFlagCameraSeesEmitters;
  if (o.cameraSeesSpecular) flags |= kFlagCameraSeesSpecular;
  if (o.captureMetalsAsDiffuse) flags |= kFlagCaptureMetalsAsDiffuse;
  if (o.spp == 1) flags |= kFlagPixelCenter;
  if (r.transmits) flags |= kFlagTransmits;
  p.path = {std::max(0, o.bounces), static_cast<int>(o.only), flags, static_cast<int>(o.seed)};
  // The albedo tables of this render's sheen visibility, after the environment's: uploaded
  // again only when it changes (the viewer resets at every move of the camera).
  if (static_cast<int>(o.sheenVisibility) != r.albedoVisibility) {
    const shared::AlbedoTables albedo = referenceAlbedoTables(o.sheenVisibility);
    constexpr std::size_t kNodes =
        std::size_t{shared::kAlbedoTableNodes} * shared::kAlbedoTableNodes;
    std::vector<float>& all = r.tableHost;
    const auto envFloats = static_cast<std::ptrdiff_t>(
        all.size() - r.iesFloats - std::size(shared::kCharlieProjectedArea) - 2 * kNodes);
    std::copy(albedo.ggx, albedo.ggx + kNodes, all.begin() + envFloats);
    std::copy(albedo.sheen, albedo.sheen + kNodes,
              all.begin() + envFloats + static_cast<std::ptrdiff_t>(kNodes));
    r.tables->upload(all.data(), all.size() * sizeof(float));
    r.albedoVisibility = static_cast<int>(o.sheenVisibility);
  }
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * camera.height;
  if (!r.accumulation || r.accumulation->size() != 2 * pixels * sizeof(glm::vec4))
    r.accumulation = std::make_unique<Buffer>(r.context, 2 * pixels * sizeof(glm::vec4));
  const std::vector<glm::vec4> zeros(2 * pixels, glm::vec4(0.0f));
  r.accumulation->upload(zeros.data(), zeros.size() * sizeof(glm::vec4));
  r.width = camera.width;
  r.height = camera.height;
  r.spp = 0;
  r.milliseconds = 0.0;
}

void PathTracer::accumulate(int samples) {
  Impl& r = *impl_;
  if (r.width == 0) fail("render", "the GPU reference has no view: call reset() first");
  if (samples < 1) return;
  const auto start = std::chrono::steady_clock::now();
  // Few samples per invocation. On a CPU device one: llvmpipe (Mesa 22.3, lavapipe) runs at most
  // 65535 loop iterations per invocation in all, counted over every loop of the inlined shader
  // (LP_MAX_TGSI_LOOP_ITERATIONS), and then leaves each loop after one iteration without a word:
  // 64 samples of a closed room's deep paths in one invocation returned 13 % less light. On a
  // GPU eight: short dispatches keep its watchdog away.
  const int perDispatch = r.context.device().type == "cpu" ? 1 : 8;
  for (int done = 0; done < samples;) {
    const int n = std::min(perDispatch, samples - done);
    r.parameters.image.z = static_cast<std::uint32_t>(r.spp + done);
    r.parameters.image.w = static_cast<std::uint32_t>(n);
    r.parametersBuffer->upload(&r.parameters, sizeof(SceneParameters));
    dispatch(r.context, "path_trace",
             {r.parametersBuffer.get(), r.scene.nodes.get(), r.scene.triangles.get(),
              r.scene.sceneData.get(), r.scene.words.get(), r.texels.get(), r.levels.get(),
              r.tables.get(), r.accumulation.get()},
             {}, groups(static_cast<std::size_t>(r.width), 8),
             groups(static_cast<std::size_t>(r.height), 8));
    done += n;
  }
  r.spp += samples;
  r.milliseconds +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

int PathTracer::samplesPerPixel() const {
  return impl_->spp;
}

RenderResult PathTracer::result() const {
  const Impl& r = *impl_;
  RenderResult out;
  out.color = Image(std::max(r.width, 1), std::max(r.height, 1));
  const std::size_t pixels = static_cast<std::size_t>(r.width) * r.height;
  out.alpha.assign(pixels, 0.0f);
  if (r.spp == 0 || pixels == 0) return out;
  const auto sums = r.accumulation->read<glm::vec4>(2 * pixels);
  const float inv = 1.0f / static_cast<float>(r.spp);
  for (std::size_t i = 0; i < pixels; ++i) {
    out.color.pixels[i] = glm::vec3(sums[2 * i]) * inv;
    out.alpha[i] = sums[2 * i].w * inv;
  }
  out.samples = static_cast<double>(r.spp) * static_cast<double>(pixels);
  out.milliseconds = r.milliseconds;
  return out;
}

std::vector<float> PathTracer::luminanceVariance() const {
  const Impl& r = *impl_;
  const std::size_t pixels = static_cast<std::size_t>(r.width) * r.height;
  std::vector<float> variance(pixels, 0.0f);
  if (r.spp < 2) return variance;
  const auto sums = r.accumulation->read<glm::vec4>(2 * pixels);
  const double n = r.spp;
  for (std::size_t i = 0; i < pixels; ++i) {
    const double mean = sums[2 * i + 1].x / n;
    variance[i] =
        static_cast<float>(std::max(0.0, (sums[2 * i + 1].y / n - mean * mean)) * n / (n - 1.0));
  }
  return variance;
}

float PathTracer::noise() const {
  const Impl& r = *impl_;
  if (r.spp < 2) return 0.0f;
  const std::size_t pixels = static_cast<std::size_t>(r.width) * r.height;
  const auto sums = r.accumulation->read<glm::vec4>(2 * pixels);
  const double n = r.spp;
  double varianceOfMeans = 0.0, luminanceSum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < pixels; ++i) {
    if (!(sums[2 * i].w > 0.0f)) continue;
    const double mean = sums[2 * i + 1].x / n;
    varianceOfMeans += std::max(0.0, sums[2 * i + 1].y / n - mean * mean) / (n - 1.0);
    luminanceSum += mean;
    ++count;
  }
  if (count == 0 || !(luminanceSum > 0.0)) return 0.0f;
  return static_cast<float>(std::sqrt(varianceOfMeans / static_cast<double>(count)) /
                            (luminanceSum / static_cast<double>(count)));
}

RenderResult renderReference(Context& context, const Scene& scene, const Camera& camera,
                             const BakeResult& bake, const BakeOptions& bakeOptions,
                             const RenderOptions& options,
                             const std::function<void(float)>& progress) {
  PathTracer tracer(context, scene, bake, bakeOptions);
  tracer.reset(camera, options);
  const int spp = std::max(1, options.spp);
  // Batches short enough for a device that watches its queue (a few hundred ms each on
  // lavapipe at 512 x 512), long enough to keep it busy.
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * camera.height;
  const int batch = static_cast<int>(
      std::clamp<std::size_t>((std::size_t{1} << 20u) / std::max<std::size_t>(pixels, 1), 1, 64));
  for (int done = 0; done < spp;) {
    const int n = std::min(batch, spp - done);
    tracer.accumulate(n);
    done += n;
    if (progress) progress(static_cast<float>(done) / static_cast<float>(spp));
  }
  return tracer.result();
}

}  // namespace ibl::gpu
