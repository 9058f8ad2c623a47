#pragma once
// API: stable
// Convolutions of an environment for image-based lighting: the GGX-prefiltered specular cube
// map of the split-sum approximation (Karis 2013) and the irradiance cube map.
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "ibl/core/progress.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/shared/brdf.h"

namespace ibl {

// Babylon.js's lodGenerationScale (HDRFiltering, and the default of .env files).
inline constexpr float kBabylonLodGenerationScale = 0.8f;

// Roughness of mip level m of L prefiltered levels. Roughness throughout: perceptual (glTF's
// roughnessFactor), 0 to 1; the GGX alpha is its square.
enum class RoughnessMapping {
  Linear,     // r = m / (L - 1) (the default)
  Frostbite,  // r = (m / (L - 1))^2, i.e. level = sqrt(r) (L - 1) (Lagarde & de Rousiers 2014)
  // Filament's: lod = (L - 1) r (2 - r), i.e. r = 1 - sqrt(1 - m / (L - 1)) (Filament's
  // perceptualRoughnessToLod in shaders/src/light_indirect.fs; cmgen's lodToPerceptualRoughness).
  Filament,
  // Babylon.js's, for a full chain (width 2^(L - 1) down to 1): lod = 0.8 log2(width alpha) with
  // alpha = r^2 (its getLodFromAlphaG and lodGenerationScale 0.8), i.e. level m >= 1 holds
  // alpha = 2^(m / 0.8) / width (its HDRFiltering), capped at r = 1; level 0 holds r = 0.
  Babylon,
};
// "linear", "frostbite", "filament", "babylon"
std::string_view mappingName(RoughnessMapping mapping);
// level: 0 to levelCount - 1; 0 when levelCount <= 1.
float roughnessForLevel(int level, int levelCount, RoughnessMapping mapping);
// The mip level (fractional, 0 to levelCount - 1) that holds roughness r: the inverse of
// roughnessForLevel.
float specularLodForRoughness(float roughness, int levelCount, RoughnessMapping mapping);

// What each specular level averages the environment with (the split sum's first factor).
enum class PrefilterWeight {
  Standard,       // D(h) (n.l): Karis 2013, n = v = r
  FresnelF0Zero,  // D V F (n.l) with F0 = 0: keeps the Fresnel/visibility weight C(n, l)
  FresnelF0One,   // D V F (n.l) with F0 = 1 (F = 1)
  Charlie,        // D_charlie(h) (n.l): the sheen lobe (Estevez & Kulla 2017), as glTF-IBL-Sampler
};

// The sheen chain's smallest roughness (ibl/shared/brdf.h).
using shared::kMinSheenRoughness;

// How a specular level was computed (reported in the manifest).
struct LevelMethod {
  float roughness = 0.0f;
  std::string method;    // "source", "direct", "rings", "sampled"
  int sourceSize = 0;    // size of the source level read, texels per side
  int samples = 0;       // samples per texel ("sampled")
  int computedSize = 0;  // texels per side it was computed at (interpolated up, if smaller)
};

enum class PrefilterMethod {
  Direct,   // quadrature over source texels, in rings for sharp lobes (prefilterLevelRings)
  Sampled,  // filtered importance sampling (prefilterLevelSampled)
};

struct PrefilterOptions {
  int size = 256;  // texels per side of level 0, a power of two
  int levels = 0;  // 0: down to kMinSpecularSize; at most the full chain (fullMipCount)
  RoughnessMapping mapping = RoughnessMapping::Linear;
  PrefilterWeight weight = PrefilterWeight::Standard;
  PrefilterMethod method = PrefilterMethod::Direct;
  int samples = 64;  // GGX samples per texel with PrefilterMethod::Sampled
};

inline constexpr int kMinSpecularSize = 8;  // texels per side
// Levels from `size` (texels per side) down to kMinSpecularSize (or 1 level if size is smaller).
int defaultSpecularLevels(int size);
// The number of specular levels `options` asks for (options.levels, or the default).
int specularLevelCount(const PrefilterOptions& options);

// Prefiltered specular cube map: level m holds the environment averaged with the GGX lobe of
// roughness roughnessForLevel(m) around n = v = r. Level 0 (r = 0) is the source itself.
// `source` must hold a full mip chain (buildMipChain) of a power-of-two size. `methods`, if
// given, receives one entry per level; `progress` hears of each level. Throws Error
// ("prefilter: ...") when options.size is not a power of two or the source's chain is not full.
CubeMap prefilterGgx(const CubeMap& source, const PrefilterOptions& options,
                     std::vector<LevelMethod>* methods = nullptr, const ProgressFn& progress = {});

// The chain of `options`: level 0 (r = 0) taken from the source (the mirror reflection), every
// other level computed by `level(size, roughness, method)`, which also fills in how. The loop
// shared by prefilterGgx and its GPU twin; checks the source's mip chain and the size (throws
// Error("prefilter: ...") as prefilterGgx). size: texels per side of the level asked for.
using SpecularLevelFn =
    std::function<std::array<Image, kFaceCount>(int size, float roughness, LevelMethod& method)>;
CubeMap buildSpecularChain(const CubeMap& source, const PrefilterOptions& options,
                           const SpecularLevelFn& level, std::vector<LevelMethod>* methods,
                           const ProgressFn& progress = {});

// Direct convolution of one specular level over every texel of source level `sourceLevel`:
// sum L w / sum w with w = weight(n.l) x texel solid angle. The reference for the tests and
// the accuracy benchmark, and the method for rough levels. size: texels per side of the
// output; sourceLevel must exist (not checked).
std::array<Image, kFaceCount> prefilterLevelDirect(const CubeMap& source, int sourceLevel, int size,
                                                   float roughness, PrefilterWeight weight);

// A radial window in c = cos(theta) around each output direction: smoothstep(outer) -
// smoothstep(inner), each smoothstep rising from 0 at c = lo to 1 at c = lo + 1 / inv. The
// windows of consecutive rings add up to 1, so every direction is counted once whatever level
// each ring reads. The default is 1 everywhere. lo: a cosine; inv: 1 / the width of the rise.
struct RadialWindow {
  float outerLo = -3.0f, outerInv = 1.0f;
  float innerLo = 2.0f, innerInv = 1.0f;
};

// Per output texel, the sums of L w and of w (in x) of one convolution pass; w is the lobe's
// weight times the texel's solid angle (sr).
struct ConvolutionSums {
  std::array<Image, kFaceCount> sum;
  std::array<Image, kFaceCount> weight;
};

// One convolution pass: every texel n of an output level of `size` against the texels l of
// `sourceLevel` within angle acos(cosCap) of it (all of them when cosCap <= 0), weighted by
// w = lobe(n.l) x window(n.l) x texel solid angle, the lobe of `roughness` and `weight`. The
// unit of work of prefilterLevelRings; gpu::convolvePass is its twin.
ConvolutionSums convolvePass(const std::array<Image, kFaceCount>& sourceLevel, int size,
                             float roughness, PrefilterWeight weight, RadialWindow window,
                             float cosCap);
using ConvolutionPassFn = std::function<ConvolutionSums(
    const std::array<Image, kFaceCount>& sourceLevel, int size, float roughness,
    PrefilterWeight weight, RadialWindow window, float cosCap)>;

// The same integral, computed in rings for sharp lobes: the lobe's core over a fine source
// level, then rings [b, 4b] of growing radius (b doubling) over ever coarser levels, at ever
// coarser output resolution, blended by smooth radial windows that add up to 1. The cost no
// longer grows with the source resolution times the output resolution. The passes run with
// `pass` (default: convolvePass, on the CPU). size: texels per side of the output; `info`, if
// given, receives how the level was computed.
std::array<Image, kFaceCount> prefilterLevelRings(const CubeMap& source, int size, float roughness,
                                                  PrefilterWeight weight,
                                                  LevelMethod* info = nullptr,
                                                  const ConvolutionPassFn& pass = {});

// The same convolution for arbitrary directions (brute-force references: pass level 0);
// directions: unit, one result per direction.
std::vector<glm::vec3> prefilterDirections(const std::array<Image, kFaceCount>& sourceLevel,
                                           std::span<const glm::vec3> directions, float roughness,
                                           PrefilterWeight weight);
// E(n) / pi for arbitrary unit directions, by direct convolution over a source level.
std::vector<glm::vec3> irradianceDirections(const std::array<Image, kFaceCount>& sourceLevel,
                                            std::span<const glm::vec3> directions);

// The sample set of filtered importance sampling for one level, in the tangent frame (z = n):
// reflected directions of `samples` Hammersley GGX half vectors, the source lod each reads
// (0.5 log2(sample solid angle / level-0 texel solid angle) + 1), and weights (n.l, times V F
// for the C(n, l) variants). Shared by the CPU and GPU paths.
struct FisSample {
  glm::vec3 l;  // unit, tangent frame
  float lod;    // source mip level, fractional, clamped to the chain
  float weight;
};
// sourceSize: texels per side of source level 0; sourceLevels: its mip levels. Samples below
// the horizon are left out (fewer than `samples` may come back).
std::vector<FisSample> filteredImportanceSamples(int sourceSize, int sourceLevels, float roughness,
                                                 int samples, PrefilterWeight weight);

// Filtered importance sampling of one specular level (Krivanek & Colbert 2008): `samples`
// Hammersley GGX samples per texel, each read from the source mip whose texel solid angle
// matches the sample's (in `source`'s mip chain); size: texels per side of the output.
std::array<Image, kFaceCount> prefilterLevelSampled(const CubeMap& source, int size,
                                                    float roughness, int samples,
                                                    PrefilterWeight weight);

// Irradiance cube map storing E(n) / pi (a white Lambertian surface's radiance), by direct
// convolution with the clamped cosine over source level `sourceLevel`. `progress` gets the
// fraction of the texels done, as stage "irradiance NxN". size: texels per side of the one
// output level (in the source's radiance units); sourceLevel must exist (not checked).
CubeMap convolveIrradiance(const CubeMap& source, int size, int sourceLevel,
                           const ProgressFn& progress = {});

// Index of the first level of `cube` no larger than `size` texels per side (the last level if
// none).
int levelOfSize(const CubeMap& cube, int size);

}  // namespace ibl
