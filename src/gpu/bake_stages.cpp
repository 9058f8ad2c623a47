// The bake stages on the GPU: the host side of shaders/{env,bake}/*.comp.
#include <map>

#include <fmt/format.h>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "gpu/buffers.hpp"
#include "ibl/core/error.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/math/brdf.hpp"

namespace ibl::gpu {

namespace {

// A cube level as the shaders read it: (direction, solid angle) and radiance per texel.
struct TexelBuffers {
  std::vector<glm::vec4> dirOmega, radiance;
  explicit TexelBuffers(const std::array<Image, kFaceCount>& level) {
    const int n = level[0].width;
    const std::vector<double> omega = faceTexelSolidAngles(n);
    for (int f = 0; f < kFaceCount; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          dirOmega.emplace_back(texelDirection(f, x, y, n),
                                static_cast<float>(omega[static_cast<std::size_t>(y) * n + x]));
          radiance.emplace_back(level[f].at(x, y), 1.0f);
        }
  }
};

}  // namespace

Image integrateDfgLut(Context& context, int width, int height, int samples) {
  Buffer lut(context, static_cast<std::size_t>(width) * height * sizeof(glm::vec4));
  const struct {
    std::uint32_t width, height, samples;
  } params{static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height),
           static_cast<std::uint32_t>(samples)};
  dispatch(context, "dfg", {&lut}, bytesOf(params), groups(width, 8), groups(height, 8));
  const auto texels = lut.read<glm::vec4>(static_cast<std::size_t>(width) * height);
  Image out(width, height);
  for (std::size_t i = 0; i < texels.size(); ++i) out.pixels[i] = glm::vec3(texels[i]);
  return out;
}

CubeMap convolveIrradiance(Context& context, const CubeMap& source, int size, int sourceLevel) {
  const TexelBuffers src(source.levels[sourceLevel]);
  std::vector<glm::vec4> targets;
  for (int f = 0; f < kFaceCount; ++f)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) targets.emplace_back(texelDirection(f, x, y, size), 0.0f);
  Buffer dirs = Buffer::of(context, src.dirOmega), radiance = Buffer::of(context, src.radiance),
         normals = Buffer::of(context, targets),
         result(context, targets.size() * sizeof(glm::vec4));
  const struct {
    std::uint32_t sourceCount, targetCount;
  } params{static_cast<std::uint32_t>(src.dirOmega.size()),
           static_cast<std::uint32_t>(targets.size())};
  dispatch(context, "irradiance", {&dirs, &radiance, &normals, &result}, bytesOf(params),
           groups(targets.size(), 64));
  const auto values = result.read<glm::vec4>(targets.size());
  CubeMap out(size, 1);
  std::size_t i = 0;
  for (int f = 0; f < kFaceCount; ++f)
    for (auto& p : out.levels[0][f].pixels) p = glm::vec3(values[i++]);
  return out;
}

Sh9 projectSh9(Context& context, const CubeMap& cube, int level) {
  const TexelBuffers src(cube.levels[level]);
  const std::uint32_t workgroups = groups(src.dirOmega.size(), 64);
  Buffer dirs = Buffer::of(context, src.dirOmega), radiance = Buffer::of(context, src.radiance),
         partials(context, static_cast<std::size_t>(workgroups) * 9 * sizeof(glm::vec4));
  const std::uint32_t count = static_cast<std::uint32_t>(src.dirOmega.size());
  dispatch(context, "sh_project", {&dirs, &radiance, &partials}, bytesOf(count), workgroups);
  const auto sums = partials.read<glm::vec4>(static_cast<std::size_t>(workgroups) * 9);
  std::array<glm::dvec3, 9> total{};
  for (std::uint32_t g = 0; g < workgroups; ++g)  // a fixed order: the same bits every run
    for (int k = 0; k < 9; ++k) total[k] += glm::dvec3(sums[g * 9 + k]);
  Sh9 sh;
  for (int k = 0; k < 9; ++k) sh[k] = glm::vec3(total[k]);
  return sh;
}

namespace {

// Every level of a cube, flattened: faces, rows, texels; levels one after another.
std::vector<glm::vec4> flatten(const CubeMap& cube, std::vector<glm::uvec2>* levels) {
  std::vector<glm::vec4> out;
  for (const auto& level : cube.levels) {
    if (levels)
      levels->push_back(
          {static_cast<std::uint32_t>(level[0].width), static_cast<std::uint32_t>(out.size())});
    for (const auto& face : level)
      for (const auto& p : face.pixels) out.emplace_back(p, 1.0f);
  }
  return out;
}

std::array<Image, kFaceCount> unflatten(const std::vector<glm::vec4>& texels, int n) {
  std::array<Image, kFaceCount> out;
  std::size_t i = 0;
  for (auto& face : out) {
    face = Image(n, n);
    for (auto& p : face.pixels) p = glm::vec3(texels[i++]);
  }
  return out;
}

}  // namespace

CubeMap resampleToCube(Context& context, const Environment& env, int size, float rotateDegrees) {
  const CubeResamplePlan plan = planResampleToCube(env, size);
  // The source texels: the panorama, or the cube level (with its one-entry level table).
  std::vector<glm::vec4> texels;
  std::vector<glm::uvec2> levelTable{{0u, 0u}};
  if (env.isCube()) {
    CubeMap level;
    level.levels = {plan.cubeLevel};
    texels = flatten(level, nullptr);
    levelTable[0].x = static_cast<std::uint32_t>(plan.cubeLevel[0].width);
  } else {
    for (const auto& p : plan.equirect.pixels) texels.emplace_back(p, 1.0f);
  }
  Buffer source = Buffer::of(context, texels), levels = Buffer::of(context, levelTable),
         weights = Buffer::of(context, plan.weights),
         result(context, static_cast<std::size_t>(6) * size * size * sizeof(glm::vec4));
  // Directions are looked up in the source's frame: the inverse of the rotation about +Y.
  const glm::mat3 toSource = glm::transpose(rotationY(rotateDegrees));
  const struct {
    std::uint32_t size, k, width, height;
    std::uint32_t k2, pad[3];
    glm::vec4 toSource[3];  // columns
  } params{
      static_cast<std::uint32_t>(size),
      static_cast<std::uint32_t>(plan.samplesPerSide),
      static_cast<std::uint32_t>(plan.equirect.width),
      static_cast<std::uint32_t>(plan.equirect.height),
      static_cast<std::uint32_t>(plan.refinedSamplesPerSide),
      {0u, 0u, 0u},
      {glm::vec4(toSource[0], 0.0f), glm::vec4(toSource[1], 0.0f), glm::vec4(toSource[2], 0.0f)}};
  dispatch(context, env.isCube() ? "cube_to_cube" : "equirect_to_cube",
           {&source, &levels, &weights, &result}, bytesOf(params), groups(size, 8), groups(size, 8),
           6);
  const std::vector<glm::vec4> texelsOut =
      result.read<glm::vec4>(static_cast<std::size_t>(6) * size * size);
  std::vector<std::uint8_t> steep(texelsOut.size());
  for (std::size_t i = 0; i < steep.size(); ++i) steep[i] = texelsOut[i].w > 0.5f ? 1 : 0;
  CubeMap out;
  out.levels.push_back(unflatten(texelsOut, size));
  // On the host, as resampleToCube does.
  unsharpAreaBlur(out, steep);
  moveNegativeLobesToPeaks(out);
  return out;
}

void buildMipChain(Context& context, CubeMap& cube) {
  const int size = cube.size();
  if (size <= 0 || (size & (size - 1)) != 0)
    fail("mip chain", "cube map size must be a power of two");
  cube.levels.resize(1);
  std::vector<glm::vec4> parent = flatten(cube, nullptr);
  for (int np = size; np > 1; np /= 2) {
    const int n = np / 2;
    const std::vector<double> exact = faceTexelSolidAngles(np);
    const std::vector<float> omega(exact.begin(), exact.end());
    Buffer in = Buffer::of(context, parent), weights = Buffer::of(context, omega),
           out(context, static_cast<std::size_t>(6) * n * n * sizeof(glm::vec4));
    const std::uint32_t childSize = static_cast<std::uint32_t>(n);
    dispatch(context, "cube_mip", {&in, &weights, &out}, bytesOf(childSize), groups(n, 8),
             groups(n, 8), 6);
    parent = out.read<glm::vec4>(static_cast<std::size_t>(6) * n * n);
    cube.levels.push_back(unflatten(parent, n));
  }
}

CubeMap prefilterGgxSampled(Context& context, const CubeMap& source, const PrefilterOptions& o,
                            std::vector<LevelMethod>* methods) {
  std::vector<glm::uvec2> levelTable;
  Buffer texels = Buffer::of(context, flatten(source, &levelTable));
  Buffer levelBuffer = Buffer::of(context, levelTable);
  const auto level = [&](int size, float r, LevelMethod& method) {
    std::vector<glm::vec4> samples;
    for (const FisSample& s :
         filteredImportanceSamples(source.size(), source.levelCount(), r, o.samples, o.weight)) {
      samples.emplace_back(s.l, s.lod);
      samples.emplace_back(s.weight, 0.0f, 0.0f, 0.0f);
    }
    Buffer sampleBuffer = Buffer::of(context, samples),
           result(context, static_cast<std::size_t>(6) * size * size * sizeof(glm::vec4));
    const struct {
      std::uint32_t size, sampleCount, levelCount;
    } params{static_cast<std::uint32_t>(size), static_cast<std::uint32_t>(samples.size() / 2),
             static_cast<std::uint32_t>(source.levelCount())};
    dispatch(context, "prefilter_fis", {&texels, &levelBuffer, &sampleBuffer, &result},
             bytesOf(params), groups(size, 8), groups(size, 8), 6);
    method = {r, "sampled", source.size(), o.samples};
    return unflatten(result.read<glm::vec4>(static_cast<std::size_t>(6) * size * size), size);
  };
  return buildSpecularChain(source, o, level, methods);
}

ConvolutionSums convolvePass(Context& context, const std::array<Image, kFaceCount>& sourceLevel,
                             int size, float roughness, PrefilterWeight weight, RadialWindow window,
                             float cosCap) {
  const TexelBuffers src(sourceLevel);
  Buffer dirs = Buffer::of(context, src.dirOmega), radiance = Buffer::of(context, src.radiance);
  return convolvePass(context, dirs, radiance, sourceLevel[0].width, size, roughness, weight,
                      window, cosCap);
}

ConvolutionSums convolvePass(Context& context, Buffer& dirOmega, Buffer& radiance, int sourceSize,
                             int size, float roughness, PrefilterWeight weight, RadialWindow window,
                             float cosCap) {
  std::vector<glm::vec4> targets;
  for (int f = 0; f < kFaceCount; ++f)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) targets.emplace_back(texelDirection(f, x, y, size), 0.0f);
  Buffer targetBuffer = Buffer::of(context, targets),
         result(context, targets.size() * sizeof(glm::vec4));
  // LobeWeight::forLevel and the window modes of accumulateTile (src/bake/prefilter.cpp).
  const float alpha = alphaFromRoughness(
      weight == PrefilterWeight::Charlie ? std::max(roughness, kMinSheenRoughness) : roughness);
  const bool windowed = window.outerLo > -2.0f || window.innerLo < 1.5f;
  const struct {
    std::uint32_t sourceSize, targetCount, kind, windowMode;
    float a2, outerLo, outerInv, innerLo, innerInv, cosCap;
  } params{static_cast<std::uint32_t>(sourceSize),
           static_cast<std::uint32_t>(targets.size()),
           weight == PrefilterWeight::Standard       ? 1u
           : weight == PrefilterWeight::FresnelF0One ? 2u
           : weight == PrefilterWeight::Charlie      ? 4u
                                                     : 3u,
           !windowed ? 0u : (window.innerLo > 1.5f ? 1u : 2u),
           alpha * alpha,
           window.outerLo,
           window.outerInv,
           window.innerLo,
           window.innerInv,
           cosCap};
  dispatch(context, "convolve_pass", {&dirOmega, &radiance, &targetBuffer, &result},
           bytesOf(params), groups(targets.size(), 64));
  const auto sums = result.read<glm::vec4>(targets.size());
  ConvolutionSums out;
  std::size_t i = 0;
  for (int f = 0; f < kFaceCount; ++f) {
    out.sum[f] = Image(size, size);
    out.weight[f] = Image(size, size);
    for (std::size_t p = 0; p < out.sum[f].pixels.size(); ++p, ++i) {
      out.sum[f].pixels[p] = glm::vec3(sums[i]);
      out.weight[f].pixels[p] = glm::vec3(sums[i].w, 0.0f, 0.0f);
    }
  }
  return out;
}

CubeMap prefilterGgx(Context& context, const CubeMap& source, const PrefilterOptions& o,
                     std::vector<LevelMethod>* methods, const ProgressFn& progress) {
  if (o.method == PrefilterMethod::Sampled) return prefilterGgxSampled(context, source, o, methods);
  // Each source level is uploaded once, the first time a pass reads it.
  std::map<const Image*, std::pair<Buffer, Buffer>> uploaded;
  const ConvolutionPassFn pass = [&](const std::array<Image, kFaceCount>& level, int size,
                                     float roughness, PrefilterWeight weight, RadialWindow window,
                                     float cosCap) {
    auto found = uploaded.find(&level[0]);
    if (found == uploaded.end()) {
      const TexelBuffers src(level);
      found = uploaded
                  .emplace(&level[0], std::pair{Buffer::of(context, src.dirOmega),
                                                Buffer::of(context, src.radiance)})
                  .first;
    }
    return convolvePass(context, found->second.first, found->second.second, level[0].width, size,
                        roughness, weight, window, cosCap);
  };
  const auto level = [&](int size, float r, LevelMethod& method) {
    return prefilterLevelRings(source, size, r, o.weight, &method, pass);
  };
  return buildSpecularChain(source, o, level, methods, progress);
}

}  // namespace ibl::gpu
