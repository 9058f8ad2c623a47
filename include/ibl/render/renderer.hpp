#pragma once
// API: stable
// A CPU renderer for materials lit by an environment, in two modes: the real-time split-sum
// approximation reading the baked assets, and a Monte Carlo reference of the full integral.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "ibl/bake/bake.hpp"
#include "ibl/render/ambient_occlusion.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/scene.hpp"
#include "ibl/render/screen_space_reflections.hpp"
#include "ibl/render/shadows.hpp"
#include "ibl/render/transmission_frame.hpp"
#include "ibl/shared/split_sum.h"

namespace ibl {

struct LocalProbe;        // probe.hpp
struct IrradianceVolume;  // irradiance_volume.hpp

enum class RenderMode { SplitSum, Reference };
enum class DiffuseModel { Disney, Lambert };
// Which lobes to shade: all, or one alone (the sheen layer alone leaves out the layer below).
enum class ShadingTerms { Both, Diffuse, Specular, Sheen };
enum class IrradianceSource { Cube, Sh };
// The real-time approximation of sphere, disk, tube and rect lights: Frostbite's (illuminance
// formulas and a representative point) or linearly transformed cosines (ltc.hpp).
enum class AreaLightModel { Frostbite, Ltc };
// Multiple scattering between microfacets, the same choice for both modes' material:
//   Off: single-scattering GGX alone (both modes);
//   Scale: the reference scales the single-scattering lobe by 1 + F0 (1 / E(n.v) - 1)
//     (Fdez-Aguera 2019), the split sum's own energy compensation;
//   Walk: the reference's lobe is Heitz et al. 2016's random walk on the microsurface (its
//     multiple scattering exactly, src/render/microfacet_walk.hpp); the split sum keeps its
//     compensation as with Scale.
enum class MultipleScattering { Off, Scale, Walk };

struct RenderOptions {
  RenderMode mode = RenderMode::SplitSum;
  DiffuseModel diffuse = DiffuseModel::Disney;
  ShadingTerms only = ShadingTerms::Both;
  int spp = 4;                  // samples per pixel (reference: the maximum)
  float noiseThreshold = 0.0f;  // reference: stop a pixel when its relative standard error is below
  // (a fraction, e.g. 0.01; checked from 16 samples on; 0: always take spp)
  // Both modes (the split sum compensates for Scale and Walk alike); the commands' default is
  // Walk.
  MultipleScattering multipleScattering = MultipleScattering::Scale;
  bool dominantDirections = true;  // split sum: Frostbite's dominant directions
  bool specularOcclusion = true;   // split sum: from the occlusion texture
  // Both modes: f90 = saturate(50 dot(F0, 0.33)) in the Fresnel (shared::fresnelF90), for the
  // cavities a low F0 stands for; off (glTF's Fresnel, f90 = 1) by default.
  bool specularMicroOcclusion = false;
  // Split sum: specular antialiasing, the GGX lobes widened by the shading normal's change across
  // the pixel (ibl/shared/specular_antialiasing.h); the commands' default is on.
  bool specularAntialiasing = false;
  IrradianceSource irradiance = IrradianceSource::Cube;
  AreaLightModel areaLights = AreaLightModel::Ltc;  // split sum (measured closer: docs/lights.md)
  // The sheen lobe's visibility: the split sum's lights, the reference. A split sum must use
  // the bake's (BakeOptions::sheenVisibility, its sheen table's): renderRays refuses another.
  SheenVisibility sheenVisibility = SheenVisibility::Charlie;
  bool shadows = false;  // reference: ray-traced visibility of the environment and the lights
  // Split sum: the lights' shadows (render/shadows.hpp; the commands' default is Map), the maps'
  // size and cascades, and the rays per light of ShadowMode::Ray.
  ShadowMode realTimeShadows = ShadowMode::None;
  ShadowSettings shadowSettings;
  // Split sum with ShadowMode::Map: maps built beforehand for these lights (the scene's, in
  // order); null: renderScene builds them for its camera (renderRays: over the whole scene).
  const ShadowMaps* shadowMaps = nullptr;
  // Reference: bounces of indirect light between the scene's surfaces (0: direct light only;
  // any bounce implies shadows). The command's default is 4.
  int bounces = 0;
  // Reference: the camera sees the surfaces' specular reflection (a probe capture leaves it
  // out: it depends on the view, Frostbite section 4.9.3).
  bool cameraSeesSpecular = true;
  // Reference, with cameraSeesSpecular false (a probe capture): the surfaces the camera sees
  // shade a metal as a diffuse surface of albedo F0 (Frostbite 4.9.1.2); false leaves metals
  // black, for measuring the rule.
  bool captureMetalsAsDiffuse = true;
  // The camera sees the area lights and the sun (a probe capture does not: the split sum adds
  // the lights' own reflections analytically).
  bool cameraSeesEmitters = true;
  // Split sum: local probes (probe.hpp), smallest influence first, composed before the distant
  // environment; with parallax correction along the proxies and distance-based roughness.
  const std::vector<LocalProbe>* probes = nullptr;
  bool parallaxCorrection = true;
  bool distanceRoughness = true;
  // Split sum: an irradiance volume (irradiance_volume.hpp). Where it covers, it gives the
  // diffuse light, and the specular of the probes and the distant environment is scaled by the
  // ratio of its irradiance to theirs (ibl/shared/irradiance_volume.h, volumeSpecularScale).
  const IrradianceVolume* volume = nullptr;
  // Split sum: ambient occlusion by casting this many rays per pixel over the hemisphere (up to
  // aoDistance; 0: a tenth of the scene's size) where the material has no occlusion texture.
  int aoRays = 0;
  float aoDistance = 0.0f;  // scene units (meters for glTF)
  // Split sum: screen-space ambient occlusion (ambient_occlusion.hpp), computed by renderScene
  // from its camera's view buffers, min with the material's occlusion, the diffuse through the
  // multiple-bounce fit and read along the bent normal.
  ScreenAmbientOcclusionSettings screenAmbientOcclusion;
  // Split sum: that occlusion per pixel, computed beforehand (renderScene fills it in).
  const ScreenOcclusion* screenOcclusion = nullptr;
  // Split sum: screen-space reflections (screen_space_reflections.hpp), computed by renderScene
  // from a first frame without them, composed before the probes and the distant environment.
  ScreenReflectionSettings screenReflections;
  // Split sum: those reflections per pixel, computed beforehand (renderScene fills them in).
  const ScreenReflections* screenReflection = nullptr;
  // Split sum: what transmissive surfaces (KHR_materials_transmission) show behind them: the
  // opaque frame (transmission_frame.hpp), which renderScene draws first for its camera when the
  // scene has any (null: the prefiltered environment alone, as a probe capture reads it).
  const TransmissionFrame* transmissionFrame = nullptr;
  // The camera sees the transmissive surfaces (false: its rays pass through them, as for the
  // opaque frame).
  bool cameraSeesTransmissive = true;
  bool environmentLight = true;       // false (--env none): the scene's lights alone
  bool backgroundEnvironment = true;  // else backgroundColor
  glm::vec3 backgroundColor{0.0f};    // linear Rec.709 radiance, the output's units
  unsigned seed = 1;                  // of the reference's sample sequences
};

struct RenderResult {
  // Linear Rec.709 radiance, not exposed: the lights add cd/m^2 (nits), the environment its own
  // units (scale the bake with scaleBake to match).
  Image color;
  std::vector<float> alpha;   // coverage of the model per pixel, 0 to 1, row-major as color
  double samples = 0.0;       // path samples taken (reference) or pixel samples (split sum)
  double milliseconds = 0.0;  // wall time of the render
};

// Renders `scene` as seen by `camera`, lit by the baked environment (split sum: specular,
// irradiance / SH, DFG; reference and background: the source cube's level 0, taken as
// piecewise constant over its texels) and by the scene's lights (split sum: the approximations
// of ibl/shared/lights.h; reference: light_sampling.hpp with multiple importance sampling).
// Area lights and the sun are seen by the camera as their luminance. bakeOptions: those of the
// bake (its mapping, sheen visibility). progress: the fraction done, 0 to 1. Throws
// Error("camera: ...") (checkCamera) and Error("render: ...") for a bake that lacks what the
// scene needs (a sheen table) or inputs of mismatched sizes.
RenderResult renderScene(const Scene& scene, const Camera& camera, const BakeResult& bake,
                         const BakeOptions& bakeOptions, const RenderOptions& options,
                         const std::function<void(float)>& progress = {});

// The peak memory, bytes, of rendering a width x height image (pixels) with renderScene or the
// viewer (`ibl render`, `ibl view`), estimated from measured renders (docs/render.md, "Memory"):
// 60 MB besides and 176 bytes per pixel: the render's own buffers (measured 50 to 52 bytes per
// pixel), the screen-space occlusion's view buffers and result (40), the reflections' lit
// frame, view buffers and result (56) while they are computed, and the opaque frame behind
// transmissive surfaces with its chain (24). For refusing, before any work,
// a size the machine cannot hold. width, height: pixels, >= 0.
std::uint64_t renderMemoryBytes(int width, int height);

// The same for any rays: generateRay(pixel) for a point in pixels ((0, 0) the top-left corner
// of pixel (0, 0)), pixels sampled as renderScene does. A probe capture renders a cube's faces.
// width, height: pixels. Throws Error("render: ...") as renderScene.
using RayGenerator = std::function<Ray(glm::vec2 pixel)>;
RenderResult renderRays(const Scene& scene, int width, int height, const RayGenerator& generateRay,
                        const BakeResult& bake, const BakeOptions& bakeOptions,
                        const RenderOptions& options,
                        const std::function<void(float)>& progress = {});

// Throws Error("render: ...") when a split sum would read a sheen table integrated with the
// visibility `table` while `options` gives the lights' sheen lobe another (renderRays and the
// viewer call it for scenes with a sheen).
void checkSheenVisibility(SheenVisibility table, const RenderOptions& options);

// Shading of one surface point, exposed for the tests.
struct SurfacePoint {
  glm::vec3 position{0.0f};    // world, scene units (local probes and ambient occlusion read it)
  glm::vec3 normal;            // shading normal, unit
  glm::vec3 baseColor;         // linear
  float metallic;              // 0 to 1
  float roughness;             // perceptual, 0 to 1
  float occlusion = 1.0f;      // 0 (occluded) to 1
  glm::vec3 bentNormal{0.0f};  // world, unit: the irradiance's direction (0: the normal)
  // The screen-space reflection: premultiplied radiance and the share of the specular lobe it
  // holds (0: the probes and the environment take all).
  glm::vec4 screenReflection{0.0f};
  bool occlusionTexture =
      false;                   // the occlusion comes from the material (else --ao may compute it)
  glm::vec3 emissive{0.0f};    // linear radiance, the output's units
  glm::vec3 sheenColor{0.0f};  // KHR_materials_sheen (0: no sheen layer)
  float sheenRoughness = 0.0f;
  float ior = 1.5f;               // KHR_materials_ior
  float specular = 1.0f;          // KHR_materials_specular, texture applied
  glm::vec3 specularColor{1.0f};  // KHR_materials_specular, texture applied
  // KHR_materials_clearcoat, textures applied (clearcoat 0: none); the coat's unit normal (the
  // interpolated normal, or its own normal map's), on the side of `normal`. The emission above
  // is already what the coat lets through toward the ray's origin.
  float clearcoat = 0.0f;
  float clearcoatRoughness = 0.0f;
  glm::vec3 clearcoatNormal{0.0f, 0.0f, 1.0f};
  // The alpha^2 of the spread of normals the base's and the coat's normal-map texels averaged
  // (shared::normalMapAlpha2; 0 without a map), for specular antialiasing.
  float normalMapAlpha2 = 0.0f, clearcoatNormalMapAlpha2 = 0.0f;
  // KHR_materials_iridescence, textures applied (iridescence 0: none): the film's strength, index
  // and thickness (nm).
  float iridescence = 0.0f;
  float iridescenceIor = 1.3f;
  float iridescenceThickness = 400.0f;
  // KHR_materials_anisotropy, texture applied (anisotropy 0: none): the strength and the
  // direction of the larger roughness (world, unit, orthogonal to `normal`).
  float anisotropy = 0.0f;
  glm::vec3 anisotropyTangent{1.0f, 0.0f, 0.0f};
  // KHR_materials_transmission and _volume, textures applied (transmission 0: none): the share
  // transmitted; whether the mesh bounds a volume (thicknessFactor > 0; else a thin wall), its
  // thickness for the real-time paths (scene units) and its attenuation coefficient (per scene
  // unit). faceNormal: the surface's own plane (a triangle's, a sphere's normal), unit, turned to
  // the side the mesh's normals face, which a direction crosses to enter the volume; frontFace:
  // the ray met that side.
  float transmission = 0.0f;
  bool volume = false;
  float thickness = 0.0f;
  glm::vec3 attenuation{0.0f};
  glm::vec3 faceNormal{0.0f, 0.0f, 1.0f};
  bool frontFace = true;
};
// The switches of the split-sum formulas (ibl/shared/split_sum.h) that the options select; the
// viewer's frame uniforms carry the same.
shared::SplitSumSwitches splitSumSwitches(const RenderOptions& options);
// The point's material as ibl/shared/split_sum.h takes it, with ambient occlusion `occlusion`.
shared::SplitSumMaterial splitSumMaterial(const SurfacePoint& p, float occlusion);
// The real-time shading of a point from the bake: the formulas of ibl/shared/split_sum.h with
// the CPU's lookups (seam-aware trilinear in the specular chain, bilinear in the irradiance
// cube or SH9, bilinear in the DFG table). view: unit, from the point toward the eye. Returns
// the outgoing radiance (environment units). Throws Error("render: ...") for a sheen the bake
// lacks.
glm::vec3 shadeSplitSum(const SurfacePoint& p, glm::vec3 view, const BakeResult& bake,
                        const BakeOptions& bakeOptions, const RenderOptions& options);
// The real-time shading of a point at `position` (world) by the scene's lights, seen from unit
// direction `view` (toward the eye); radiance in cd/m^2 (ibl/shared/lights.h,
// IES profiles applied on the CPU); dfgTable: the bake's DFG table (read at the point's n.v and
// roughness, and the clear coat's; the LTC table is looked up here, once for all the lights). A
// sheen layer adds its lobe (shared::sheenLightRadiance) and scales the layer below by `belowScale`
// (its albedo scaling). visibility: the share of each light that reaches the point, per channel
// (its shadow, colored by what transmits; empty: all of it).
glm::vec3 shadeLightsRealTime(const SurfacePoint& p, glm::vec3 position, glm::vec3 view,
                              const std::vector<Light>& lights, const Image& dfgTable,
                              const RenderOptions& options, float belowScale = 1.0f,
                              const std::vector<glm::vec3>& visibility = {});

}  // namespace ibl
