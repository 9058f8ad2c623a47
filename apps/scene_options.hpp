#pragma once
// The options `ibl render` and `ibl view` share: the scene, the environment or bake, the camera,
// the built-in scenes' material, the split sum's switches and the exposure.
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "ibl/bake/bake.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/environment_lighting.hpp"
#include "ibl/render/framing.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/render/scene.hpp"

namespace ibl::cli {

struct SceneCliOptions {
  std::string scene;
  bool strict = false;  // what a glTF file lacks (a texture, an extension) is an error
  std::string variant;  // --variant: a KHR_materials_variants variant's name (empty: none)
  std::string env;      // empty: bundled default; "none": lights only
  // The Python module's environment array in place of the file of --env (env then holds the
  // name its messages give it, "(array)"), laid out by its shape.
  std::shared_ptr<const Image> envPixels;
  std::string lightsFile;
  std::string spotLumens = "physical";
  std::string bakeDir;
  EnvScaleOptions envScale;  // --env-intensity, --env-illuminance: of --env, or of --bake's data
  std::string camera = "perspective";
  float fov = 40.0f;
  std::optional<float> orthoWidth;  // default: fits the scene
  std::string lookFrom, lookAt, up = "0,1,0";
  std::string size = "512x512";
  int spp = 0;  // 0: the command's default
  std::string baseColor = "1,1,1";
  float metallic = 0.0f;
  float roughness = 0.5f;
  float ior = 1.5f;                 // KHR_materials_ior of the built-in scenes' material
  float specular = 1.0f;            // KHR_materials_specular's factor
  float clearcoat = 0.0f;           // KHR_materials_clearcoat's factor
  float clearcoatRoughness = 0.0f;  // and roughness
  // KHR_materials_iridescence: the film's strength, index and thickness (nm)
  float iridescence = 0.0f;
  float iridescenceIor = 1.3f;
  float iridescenceThickness = 400.0f;
  // KHR_materials_anisotropy: the strength and the rotation from the tangent (degrees)
  float anisotropy = 0.0f;
  float anisotropyRotation = 0.0f;
  // KHR_materials_transmission and _volume: the share transmitted, the thickness (scene units; 0:
  // a thin wall), the attenuation distance (scene units; infinite: none) and color (R,G,B)
  float transmission = 0.0f;
  float thickness = 0.0f;
  float attenuationDistance = std::numeric_limits<float>::infinity();
  std::string attenuationColor = "1,1,1";
  std::string diffuse = "disney";
  std::string only;
  std::string multiscatter = "walk";  // --multiscatter walk|scale|off
  bool noMultiscatter = false;        // --no-multiscatter: an alias of --multiscatter off
  bool specularMicroOcclusion = false;
  std::string specularAa = "on";  // --specular-aa on|off (split sum and viewer)
  bool noDominant = false;
  std::string irradiance = "cube";
  std::string areaLights = "ltc";
  std::string sheenVisibility;      // empty: the bake's (--bake), else charlie
  std::vector<std::string> probes;  // local probe directories (split sum)
  std::string volume;               // an irradiance volume's directory (split sum)
  int volumeUpdateFrames = 0;       // frames of the live update run on it before rendering
  // Use probes or a volume captured with another shading (a warning, not an error).
  bool force = false;
  bool noParallax = false;
  bool noDistanceRoughness = false;
  int aoRays = 0;
  std::string ssao;  // on or off; empty: on for glTF scenes without --ao, off for built-in ones
  float ssaoRadius = 0.0f;  // 0: a tenth of the scene's bounding diagonal
  std::string ssaoQuality = "medium";
  std::string ssr;  // on or off; empty: on for glTF scenes, off for built-in ones
  std::string ssrQuality = "medium";
  float ssrThickness = 0.05f;
  // --shadows none, map or ray; empty: not given (the split sum's map, the reference's none
  // with --bounces 0).
  std::string shadows;
  int shadowMapSize = 1024;
  int shadowCascades = 4;
  int shadowRays = 16;
  std::string background = "env";
  std::string ev100;  // empty: automatic
  float aperture = 0.0f, shutter = 0.0f, iso = 0.0f;
  float compensation = 0.0f;
  std::string tonemap = "aces";
  std::string bloom;  // EC (stops) or off; empty: the command's default
  // The command these options were parsed by (addSceneOptions sets it): which were given.
  const CLI::App* command = nullptr;
};

// Whether `option` ("--fov") was on the command line that o.command parsed.
bool given(const SceneCliOptions& o, const std::string& option);

// Registers --variant NAME (addSceneOptions does; `ibl probe` calls it alone), and the usage
// error for it with a built-in scene.
void addVariantOption(CLI::App* cmd, SceneCliOptions& o);
void checkVariantOption(const SceneCliOptions& o);
// Registers the shared options on `cmd` (the scene positional argument included).
void addSceneOptions(CLI::App* cmd, SceneCliOptions& o);
// Registers --multiscatter walk|scale|off and its alias --no-multiscatter (addSceneOptions does;
// `ibl probe` calls it alone) and reads the choice.
void addMultipleScatteringOptions(CLI::App* cmd, SceneCliOptions& o);
MultipleScattering multipleScatteringChoice(const SceneCliOptions& o);
// Registers --volume DIR, the irradiance volume of `ibl probe --volume`, and
// --volume-update-frames N, the frames of its live update run before rendering (`ibl render`,
// `ibl view`).
void addVolumeOption(CLI::App* cmd, SceneCliOptions& o);
// A usage error for --volume-update-frames without --volume.
void checkVolumeUpdateFrames(const SceneCliOptions& o);

glm::vec3 parseVec3(const std::string& text, const char* option);
// --size as (width, height), 1 to 16384 each.
std::pair<int, int> parseSize(const std::string& text);

// The scene, with the lights of --lights added to its own; the glTF loader's warnings printed
// (unless --quiet), or with --strict errors.
Scene loadScene(const SceneCliOptions& o, const GlobalOptions& global);
// --env none: no environment light.
bool environmentIsNone(const SceneCliOptions& o);

// The environment lighting of --bake or --env (bake, options and the environment's suns).
struct LoadedBake : EnvironmentLighting {
  EnvScale envScale;  // what --env-intensity / --env-illuminance did (factor 1: nothing)
};
// Whether --ssao (or its default) turns screen-space ambient occlusion on.
bool screenAmbientOcclusionOn(const SceneCliOptions& o);
// Whether --ssr (or its default) turns screen-space reflections on.
bool screenReflectionsOn(const SceneCliOptions& o);
// The split sum's (and the viewer's) shadows from --shadows: map unless none or ray is given.
ShadowMode realTimeShadowMode(const SceneCliOptions& o);

// Every scene option that can be checked before anything is read (usage errors): --env with
// --bake, a sky description, the size, the camera's points and up, the built-in scenes' color,
// the background, --ev100, and each option that another one makes meaningless (it would be
// ignored: --fov with --camera ortho, --aperture without --shutter and --iso, --ssao-quality
// with the occlusion off...).
void checkSceneOptions(const SceneCliOptions& o);
// A note (unless quiet) naming --tonemap, and unless the exposure is used still (`exposureUsed`:
// for the bloom's threshold) --ev100, --aperture, --shutter, --iso and --exposure-compensation,
// when they are given and the image written is not exposed: harmless (the image is right), but
// not what they ask; `image` says why ("out.exr holds linear radiance; ...").
void noteToneOptionsWithoutEffect(const SceneCliOptions& o, const std::string& image,
                                  bool exposureUsed, const GlobalOptions& global);
// Usage errors for the options `ibl render`'s mode would ignore: the split sum's with
// --mode reference (`reference`), the reference's (--bounces) without; --noise with fewer
// samples per pixel (`spp`) than it waits for; --shadows none with the reference's `bounces`.
void refuseOptionsTheModeIgnores(const SceneCliOptions& o, bool reference, int spp, int bounces,
                                 float noise);

// The --bake directory (readEnvironmentLighting), or a bake of --env (or the bundled
// environment) on the CPU (bakeEnvironmentLighting; unlitEnvironmentLighting for --env none).
// --env-intensity / --env-illuminance scale --env before it is baked, or the --bake's radiance
// (its source, specular, sheen and irradiance cubes and SH9; not the DFG tables) and its sun:
// the same result, every stage of a bake being linear in the radiance.
// `sheen`: the scene has KHR_materials_sheen materials, so the bake needs the sheen chain.
// options.sheenVisibility is the sheen lobe's visibility the render must use: --sheen-visibility
// (charlie when not given) for a bake made here; the bake's recorded one for --bake, which
// --sheen-visibility must not contradict.
LoadedBake loadOrBake(const SceneCliOptions& o, const GlobalOptions& global, bool sheen = false);

// The files a scene command reads (the glTF file, the environment, the lights file, every file
// of the --bake and --probes directories), after checking that each named one exists and can
// be read; for refusing an output that would overwrite one of them.
std::vector<std::filesystem::path> sceneInputFiles(const SceneCliOptions& o);

// The camera the options choose (--camera, --fov, --ortho-width, --look-from, --look-at, --up).
CameraChoice cameraChoice(const SceneCliOptions& o);
// The camera (ibl::frameCamera): the options, else the scene file's, else one framing the scene
// from +Z; checked, with usage errors for the options it would ignore or cannot use.
Camera frameCamera(const SceneCliOptions& o, const Scene& scene, int width, int height);

// The shading switches (mode, spp and the reference's options left at their defaults), with
// the sheen visibility of the bake (loadOrBake).
RenderOptions shadingOptions(const SceneCliOptions& o, const LoadedBake& baked);

// EV100 from --ev100, else --aperture/--shutter/--iso, else the image's average luminance.
float chooseEv100(const SceneCliOptions& o, const Image& linear);
ToneMap toneCurve(const SceneCliOptions& o);
// The bloom's exposure compensation from --bloom (none: off), else the command's default.
std::optional<float> bloomCompensation(const SceneCliOptions& o, std::optional<float> otherwise);

// Writes a rendered image: .exr (linear radiance and coverage, or the exposed image) or .png
// (exposed, tone-mapped, sRGB). Throws for other extensions.
void writeRenderedImage(const std::string& path, const RenderResult& result, float ev100,
                        ToneMap curve, bool exrExposed);
// Throws unless `path` ends in .exr or .png.
void checkRenderedImagePath(const std::string& path);

}  // namespace ibl::cli
