#include "scene_options.hpp"

#include "commands.hpp"
#include "preflight.hpp"

#include <fstream>
#include <sstream>

#include <fmt/core.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vector_relational.hpp>

#include "ibl/core/error.hpp"
#include "ibl/env/default_environment.hpp"
#include "ibl/env/photometry.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/render/gltf.hpp"

namespace ibl::cli {

void addMultipleScatteringOptions(CLI::App* cmd, SceneCliOptions& o) {
  CLI::Option* choice =
      cmd->add_option("--multiscatter", o.multiscatter,
                      "Multiple scattering between microfacets: walk (the reference: Heitz et al. "
                      "2016's random walk on the microsurface), scale (the reference: the GGX "
                      "lobe scaled by the split sum's energy compensation) or off (single "
                      "scattering in both modes); the split sum compensates for walk and scale")
          ->check(CLI::IsMember({"walk", "scale", "off"}))
          ->capture_default_str();
  cmd->add_flag("--no-multiscatter", o.noMultiscatter, "The same as --multiscatter off")
      ->excludes(choice);
}

MultipleScattering multipleScatteringChoice(const SceneCliOptions& o) {
  if (o.noMultiscatter || o.multiscatter == "off") return MultipleScattering::Off;
  return o.multiscatter == "scale" ? MultipleScattering::Scale : MultipleScattering::Walk;
}

void addVolumeOption(CLI::App* cmd, SceneCliOptions& o) {
  cmd->add_option("--volume", o.volume,
                  "Split sum: an irradiance volume (a directory written by `ibl probe --volume`) "
                  "giving the diffuse light where it covers, the probes' and environment's "
                  "specular normalized by it");
  cmd->add_option("--volume-update-frames", o.volumeUpdateFrames,
                  "Run this many frames of the volume's live update (rays from every probe, "
                  "blended with hysteresis 0.9) before rendering")
      ->check(numberIn(0, 100000));
}

void checkVolumeUpdateFrames(const SceneCliOptions& o) {
  if (o.volumeUpdateFrames > 0 && o.volume.empty())
    failUsage("--volume-update-frames", "updates the volume of --volume, which is not given");
}

void addVariantOption(CLI::App* cmd, SceneCliOptions& o) {
  cmd->add_option("--variant", o.variant,
                  "glTF: draw the materials of this KHR_materials_variants variant (`ibl info` "
                  "lists a file's variants)");
}

void addSceneOptions(CLI::App* cmd, SceneCliOptions& o) {
  o.command = cmd;
  cmd->add_option("scene", o.scene, "glTF file (.gltf, .glb), 'sphere' or 'grid'")->required();
  cmd->add_flag("--strict", o.strict,
                "Refuse a scene that ibl would render incompletely: a missing or unreadable "
                "texture, an extension ibl does not implement, triangle strips (otherwise "
                "warnings)");
  addVariantOption(cmd, o);
  cmd->add_option("--env", o.env,
                  "Environment to bake and light with (default: the bundled sunset.exr); a "
                  "physical sky, sky:elevation=30,azimuth=120 (see ibl sky; its sun is added "
                  "as a light); 'none': the lights alone, on black");
  cmd->add_option("--lights", o.lightsFile,
                  "Lights file (JSON, see docs/lights.md) added to the scene's lights");
  cmd->add_option("--spot-lumens", o.spotLumens,
                  "A spot's lumens to candela: physical (spread over its cone) or frostbite "
                  "(I = phi / pi)")
      ->check(CLI::IsMember({"physical", "frostbite"}))
      ->capture_default_str();
  cmd->add_option("--bake", o.bakeDir, "Use an existing bake directory instead of baking --env");
  addEnvScaleOptions(cmd, o.envScale);
  cmd->add_option("--camera", o.camera, "perspective or ortho")
      ->check(CLI::IsMember({"perspective", "ortho"}))
      ->capture_default_str();
  cmd->add_option("--fov", o.fov, "Vertical field of view in degrees")
      ->check(numberIn(1.0f, 179.0f))
      ->capture_default_str();
  cmd->add_option("--ortho-width", o.orthoWidth,
                  "Width of the orthographic view (default: fits the scene)")
      ->check(finiteNumber());
  cmd->add_option("--look-from", o.lookFrom,
                  "Camera position X,Y,Z (default: in front of the scene, +Z)");
  cmd->add_option("--look-at", o.lookAt, "Point looked at X,Y,Z (default: the scene's center)");
  cmd->add_option("--up", o.up, "Up vector X,Y,Z")->capture_default_str();
  cmd->add_option("--size", o.size, "Image size WxH")->capture_default_str();
  cmd->add_option("--base-color", o.baseColor, "Built-in scenes: linear base color R,G,B")
      ->capture_default_str();
  cmd->add_option("--metallic", o.metallic, "Built-in sphere: metallic")
      ->check(numberIn(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--roughness", o.roughness, "Built-in sphere: perceptual roughness")
      ->check(numberIn(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--ior", o.ior,
                  "Built-in scenes: the dielectric's index of refraction (KHR_materials_ior; F0 = "
                  "((ior - 1) / (ior + 1))^2)")
      ->check(numberIn(1.0f, 5.0f))
      ->capture_default_str();
  cmd->add_option("--specular", o.specular,
                  "Built-in scenes: the dielectric's specular strength (KHR_materials_specular; "
                  "0 leaves the diffuse alone)")
      ->check(numberIn(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--clearcoat", o.clearcoat,
                  "Built-in scenes: a clear coat's strength (KHR_materials_clearcoat: a GGX layer "
                  "of IOR 1.5 over the material)")
      ->check(numberIn(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--clearcoat-roughness", o.clearcoatRoughness,
                  "Built-in scenes: the clear coat's perceptual roughness")
      ->check(numberIn(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--iridescence", o.iridescence,
                  "Built-in scenes: a thin film's strength (KHR_materials_iridescence: its "
                  "interference colors the specular reflection)")
      ->check(numberIn(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--iridescence-ior", o.iridescenceIor,
                  "Built-in scenes: the thin film's index of refraction")
      ->check(numberIn(1.0f, 3.0f))
      ->capture_default_str();
  cmd->add_option("--iridescence-thickness", o.iridescenceThickness,
                  "Built-in scenes: the thin film's thickness in nanometers")
      ->check(numberIn(0.0f, 2000.0f))
      ->capture_default_str();
  cmd->add_option("--anisotropy", o.anisotropy,
                  "Built-in scenes: the anisotropy's strength (KHR_materials_anisotropy: the "
                  "roughness grows along the spheres' parallels)")
      ->check(numberIn(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--anisotropy-rotation", o.anisotropyRotation,
                  "Built-in scenes: the anisotropy's direction, in degrees counterclockwise from "
                  "the parallels toward the meridians")
      ->check(numberIn(-360.0f, 360.0f))
      ->capture_default_str();
  cmd->add_option("--transmission", o.transmission,
                  "Built-in scenes: the share of the light below the specular layer that passes "
                  "through the surface (KHR_materials_transmission: glass, thin plastic)")
      ->check(numberIn(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--thickness", o.thickness,
                  "Built-in scenes: 0, a thin wall; above, the spheres are solid and refract by "
                  "--ior, and the real-time paths take this thickness in scene units "
                  "(KHR_materials_volume)")
      ->check(numberIn(0.0f, 1000.0f))
      ->capture_default_str();
  cmd->add_option("--attenuation-distance", o.attenuationDistance,
                  "Built-in scenes: the distance (scene units) after which the light inside a "
                  "volume keeps --attenuation-color of itself (default: none absorbed)")
      ->check(positiveNumber());
  cmd->add_option("--attenuation-color", o.attenuationColor,
                  "Built-in scenes: the linear color R,G,B (0 to 1) left after "
                  "--attenuation-distance inside a volume")
      ->capture_default_str();
  cmd->add_option("--diffuse", o.diffuse, "disney (Frostbite renormalized) or lambert")
      ->check(CLI::IsMember({"disney", "lambert"}))
      ->capture_default_str();
  cmd->add_option("--only", o.only,
                  "Isolate a term: diffuse, specular, or sheen (the KHR_materials_sheen layer "
                  "alone)")
      ->check(CLI::IsMember({"diffuse", "specular", "sheen"}));
  addMultipleScatteringOptions(cmd, o);
  cmd->add_flag("--specular-micro-occlusion", o.specularMicroOcclusion,
                "Both modes: Schlick's f90 from F0, saturate(50 dot(F0, 0.33)), darkening the "
                "grazing reflection of materials whose F0 is below any real one's (0.02); off by "
                "default, as glTF's Fresnel");
  cmd->add_option("--specular-aa", o.specularAa,
                  "Split sum and viewer: specular antialiasing, the GGX lobes widened by how much "
                  "the shading normal (normal map included) turns across a pixel (Tokuyoshi & "
                  "Kaplanyan 2019), so that highlights do not sparkle")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--probes", o.probes,
                  "Split sum: local light probes (directories written by `ibl probe`: one probe, "
                  "or a grid with probes.json), composed before the distant environment");
  cmd->add_flag("--force", o.force,
                "Use --probes (or a --volume) captured with another shading (--diffuse, "
                "--multiscatter, --specular-micro-occlusion) than this one's: a warning instead "
                "of an error");
  cmd->add_flag("--no-parallax", o.noParallax,
                "Split sum: read the probes without parallax correction");
  cmd->add_flag("--no-distance-roughness", o.noDistanceRoughness,
                "Split sum: no distance-based roughness in the probes");
  cmd->add_option("--ao", o.aoRays,
                  "Split sum: ambient occlusion from N rays per pixel where the model has no "
                  "occlusion texture (0: none)")
      ->check(numberIn(0, 4096));
  cmd->add_option("--ssao", o.ssao,
                  "Split sum and viewer: screen-space ambient occlusion (GTAO) from the view's "
                  "depth and normals, min with the material's occlusion (default: on for glTF "
                  "scenes without --ao, off for the built-in ones)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--ssao-radius", o.ssaoRadius,
                  "The screen-space occlusion's reach in scene units (meters; default: a tenth "
                  "of the scene's bounding diagonal)")
      ->check(positiveNumber());
  cmd->add_option("--ssao-quality", o.ssaoQuality,
                  "Slices x steps per pixel: low (2 x 4), medium (4 x 6) or high (8 x 8)")
      ->check(CLI::IsMember({"low", "medium", "high"}))
      ->capture_default_str();
  cmd->add_option("--ssr", o.ssr,
                  "Split sum and viewer: screen-space reflections traced through the view's "
                  "depth, composed before the probes and the environment (default: on for glTF "
                  "scenes, off for the built-in ones)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--ssr-quality", o.ssrQuality,
                  "Rays x steps x pixels per step: low (1 x 48 x 4), medium (4 x 96 x 2) or high "
                  "(8 x 192 x 1)")
      ->check(CLI::IsMember({"low", "medium", "high"}))
      ->capture_default_str();
  cmd->add_option("--ssr-thickness", o.ssrThickness,
                  "The depth a surface is taken to have behind the depth buffer, as a share of "
                  "its distance")
      ->check(numberIn(0.001f, 10.0f))
      ->capture_default_str();
  cmd->add_option("--shadows", o.shadows,
                  "The lights' shadows. Split sum and viewer: none, map (shadow maps, the "
                  "default) or ray (ray-traced per light sample; `ibl render` only). Reference: "
                  "ray traces the visibility of the environment and the lights with --bounces 0 "
                  "(any bounce implies it), none (the default with --bounces 0) does not")
      ->check(CLI::IsMember({"none", "map", "ray"}));
  cmd->add_option("--shadow-map-size", o.shadowMapSize,
                  "Texels per side of each shadow map layer (a power of two)")
      ->check(powerOfTwo(16, 8192))
      ->capture_default_str();
  cmd->add_option("--shadow-cascades", o.shadowCascades, "The sun's shadow cascades")
      ->check(numberIn(1, 4))
      ->capture_default_str();
  cmd->add_flag("--no-dominant", o.noDominant,
                "Split sum: sample along n and r, not the dominant directions");
  cmd->add_option("--irradiance", o.irradiance,
                  "Split sum: diffuse from the irradiance cube or SH9")
      ->check(CLI::IsMember({"cube", "sh"}))
      ->capture_default_str();
  cmd->add_option("--area-lights", o.areaLights,
                  "Split sum: sphere, disk, tube and rect lights through linearly transformed "
                  "cosines (ltc, measured closer) or Frostbite's approximations (frostbite)")
      ->check(CLI::IsMember({"ltc", "frostbite"}))
      ->capture_default_str();
  cmd->add_option("--sheen-visibility", o.sheenVisibility,
                  "The sheen lobe's visibility (KHR_materials_sheen): charlie (Estevez & Kulla, "
                  "the specification's) or neubelt (simpler, gains energy at grazing angles); "
                  "default: the bake's with --bake, else charlie")
      ->check(CLI::IsMember({"charlie", "neubelt"}));
  cmd->add_option("--background", o.background, "'env' (the environment) or a color R,G,B")
      ->capture_default_str();
  cmd->add_option("--ev100", o.ev100,
                  "Exposure value at ISO 100 (default: automatic, average log luminance)");
  cmd->add_option("--aperture", o.aperture, "f-number (with --shutter and --iso)")
      ->check(positiveNumber());
  cmd->add_option("--shutter", o.shutter, "Shutter time in seconds")->check(positiveNumber());
  cmd->add_option("--iso", o.iso, "Sensitivity")->check(positiveNumber());
  cmd->add_option("--exposure-compensation", o.compensation, "Stops added to the exposure")
      ->check(finiteNumber())
      ->capture_default_str();
  cmd->add_option("--bloom", o.bloom,
                  "Bloom: the light EC stops above the average luminance the exposure is set for "
                  "spreads over a wide kernel, the image's total power unchanged; off: none "
                  "(default: off for `ibl render`, 3 for `ibl view`'s window and screenshots)");
  cmd->add_option("--tonemap", o.tonemap, "none, aces or filmic")
      ->check(CLI::IsMember({"none", "aces", "filmic"}))
      ->capture_default_str();
}

glm::vec3 parseVec3(const std::string& text, const char* option) {
  const std::vector<float> v = parseNumbers(text, 3, option);
  return {v[0], v[1], v[2]};
}

// A camera position or target: finite and within the range rays can be traced from.
glm::vec3 parsePoint(const std::string& text, const char* option) {
  const glm::vec3 p = parseVec3(text, option);
  if (glm::max(glm::abs(p.x), glm::max(glm::abs(p.y), glm::abs(p.z))) > 1e8f)
    failUsage(option,
              fmt::format("'{}' is too far from the origin (at most 1e8 per coordinate)", text));
  return p;
}

std::pair<int, int> parseSize(const std::string& text) {
  int width = 0, height = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> width >> x >> height) || x != 'x' || width < 1 || height < 1 || width > 16384 ||
      height > 16384)
    failUsage("--size", fmt::format("expected WxH (1 to 16384), got '{}'", text));
  return {width, height};
}

namespace {}  // namespace

void checkVariantOption(const SceneCliOptions& o) {
  if (!o.variant.empty() && (o.scene == "sphere" || o.scene == "grid"))
    failUsage("--variant", fmt::format("applies to a glTF scene, not the built-in '{}'", o.scene));
}

namespace {

// --attenuation-color, each channel from 0 to 1.
glm::vec3 attenuationColorOf(const SceneCliOptions& o) {
  const glm::vec3 c = parseVec3(o.attenuationColor, "--attenuation-color");
  if (glm::any(glm::lessThan(c, glm::vec3(0.0f))) || glm::any(glm::greaterThan(c, glm::vec3(1.0f))))
    failUsage("--attenuation-color",
              fmt::format("each channel must be from 0 to 1, not '{}'", o.attenuationColor));
  return c;
}

Scene loadSceneAlone(const SceneCliOptions& o, const GlobalOptions& global) {
  if (o.scene != "sphere" && o.scene != "grid") {
    GltfLoadOptions options;
    options.strict = o.strict;
    options.variant = o.variant;
    options.warn = [quiet = global.quiet](const std::string& message) {
      if (!quiet) fmt::print(stderr, "ibl: warning: {}\n", message);
    };
    return loadGltf(o.scene, options);
  }
  Material m;
  m.baseColor = parseVec3(o.baseColor, "--base-color");
  m.ior = o.ior;
  m.specular = o.specular;
  m.clearcoat = o.clearcoat;
  m.clearcoatRoughness = o.clearcoatRoughness;
  m.iridescence = o.iridescence;
  m.iridescenceIor = o.iridescenceIor;
  m.iridescenceThicknessMaximum = o.iridescenceThickness;
  m.anisotropy = o.anisotropy;
  m.anisotropyRotation = glm::radians(o.anisotropyRotation);
  m.transmission = o.transmission;
  m.thickness = o.thickness;
  m.attenuationDistance = o.attenuationDistance;
  m.attenuationColor = attenuationColorOf(o);
  if (o.scene == "grid") return makeSphereGrid(m);
  m.metallic = o.metallic;
  m.roughness = o.roughness;
  return makeSphereScene(m);
}

}  // namespace

bool environmentIsNone(const SceneCliOptions& o) {
  return o.env == "none";
}

Scene loadScene(const SceneCliOptions& o, const GlobalOptions& global) {
  // The lights file first: a mistake in it is found before a large model loads.
  std::vector<Light> lights;
  if (!o.lightsFile.empty())
    lights = readLightsFile(
        o.lightsFile, o.spotLumens == "frostbite" ? SpotLumens::Frostbite : SpotLumens::Physical);
  Scene scene = loadSceneAlone(o, global);
  scene.lights.insert(scene.lights.end(), lights.begin(), lights.end());
  return scene;
}

bool given(const SceneCliOptions& o, const std::string& option) {
  const CLI::Option* given = o.command ? o.command->get_option_no_throw(option) : nullptr;
  return given && given->count() > 0;
}

namespace {

bool builtInScene(const SceneCliOptions& o) {
  return o.scene == "sphere" || o.scene == "grid";
}

// The options that another one given makes meaningless, each a usage error naming both.
void refuseIgnoredSceneOptions(const SceneCliOptions& o) {
  // The exposure: --ev100, or the camera's three settings together.
  const std::pair<const char*, float> settings[] = {
      {"--aperture", o.aperture}, {"--shutter", o.shutter}, {"--iso", o.iso}};
  for (const auto& [option, value] : settings) {
    if (!(value > 0.0f)) continue;
    if (!o.ev100.empty())
      failUsage("--ev100", fmt::format("contradicts {} {}: each sets the exposure; pass --ev100 "
                                       "or --aperture, --shutter and --iso",
                                       option, formatNumber(value)));
    std::string missing;
    for (const auto& [other, otherValue] : settings)
      if (!(otherValue > 0.0f))
        missing += fmt::format("{}{}", missing.empty() ? "" : " and ", other);
    if (!missing.empty())
      failUsage(option, fmt::format("sets the exposure together with {}: give all three, or "
                                    "--ev100 (alone, the automatic exposure would ignore it)",
                                    missing));
  }
  // The camera's kind.
  if (o.camera == "ortho" && given(o, "--fov"))
    failUsage("--fov",
              "applies to --camera perspective; --camera ortho's view is --ortho-width "
              "wide");
  if (o.orthoWidth && (given(o, "--camera") || builtInScene(o)) && o.camera != "ortho")
    failUsage("--ortho-width", "applies to --camera ortho; --camera perspective's view is --fov");
  // The built-in scenes' material.
  for (const char* option :
       {"--base-color", "--metallic", "--roughness", "--ior", "--specular", "--clearcoat",
        "--clearcoat-roughness", "--iridescence", "--iridescence-ior", "--iridescence-thickness",
        "--anisotropy", "--anisotropy-rotation", "--transmission", "--thickness",
        "--attenuation-distance", "--attenuation-color"})
    if (given(o, option) && !builtInScene(o))
      failUsage(option, fmt::format("sets the material of the built-in scenes (sphere, grid); "
                                    "the scene {} has its own",
                                    o.scene));
    else if (given(o, option) && o.scene == "grid" &&
             (option == std::string("--metallic") || option == std::string("--roughness")))
      failUsage(option,
                "sets the built-in sphere's material; the grid varies it over its "
                "spheres");
  // KHR_materials_volume's settings need a volume, and a volume needs transmission.
  if (builtInScene(o)) {
    for (const char* option : {"--attenuation-distance", "--attenuation-color"})
      if (given(o, option) && o.thickness <= 0.0f)
        failUsage(option,
                  "sets the absorption inside a volume; add --thickness (above 0) to make the "
                  "spheres solid");
    if (given(o, "--thickness") && o.transmission <= 0.0f)
      failUsage("--thickness", "makes a transmissive sphere solid; add --transmission");
  }
  // Settings of what is off.
  const auto refuseWhenOff = [&](bool on, const char* option, const char* feature,
                                 const std::string& off) {
    if (!on && given(o, option))
      failUsage(option, fmt::format("sets the {}, which is off here ({})", feature, off));
  };
  const std::string ssaoOff = o.ssao == "off" ? "--ssao off"
                              : o.aoRays > 0  ? fmt::format("--ao {} replaces it", o.aoRays)
                                              : "the built-in scenes' default; add --ssao on";
  for (const char* option : {"--ssao-radius", "--ssao-quality"})
    refuseWhenOff(screenAmbientOcclusionOn(o), option, "screen-space occlusion", ssaoOff);
  const std::string ssrOff =
      o.ssr == "off" ? "--ssr off" : "the built-in scenes' default; add --ssr on";
  for (const char* option : {"--ssr-quality", "--ssr-thickness"})
    refuseWhenOff(screenReflectionsOn(o), option, "screen-space reflections", ssrOff);
  for (const char* option : {"--shadow-map-size", "--shadow-cascades"})
    refuseWhenOff(realTimeShadowMode(o) == ShadowMode::Map, option, "shadow maps",
                  "--shadows " + o.shadows);
  refuseWhenOff(o.shadows == "ray", "--shadow-rays", "ray-traced shadows",
                o.shadows.empty() ? "the default is --shadows map; add --shadows ray"
                                  : "--shadows " + o.shadows);
  for (const char* option : {"--no-parallax", "--no-distance-roughness"})
    refuseWhenOff(!o.probes.empty(), option, "reading of local probes", "no --probes given");
  refuseWhenOff(!o.probes.empty() || !o.volume.empty(), "--force",
                "reading of local probes or a volume", "no --probes or --volume given");
  refuseWhenOff(!o.lightsFile.empty(), "--spot-lumens", "spot lights' conversion of --lights",
                "no --lights given; a glTF file's spots are in candela");
}

}  // namespace

void noteToneOptionsWithoutEffect(const SceneCliOptions& o, const std::string& image,
                                  bool exposureUsed, const GlobalOptions& global) {
  std::vector<std::string> unused;
  if (given(o, "--tonemap")) unused.emplace_back("--tonemap");
  if (!exposureUsed)
    for (const char* option :
         {"--ev100", "--aperture", "--shutter", "--iso", "--exposure-compensation"})
      if (given(o, option)) unused.emplace_back(option);
  if (unused.empty() || global.quiet) return;
  std::string names;
  for (const std::string& name : unused) names += (names.empty() ? "" : ", ") + name;
  fmt::print(stderr, "ibl: note: {}: no effect: {}{}\n", names, image,
             exposureUsed ? "" : " (and no --bloom reads the exposure)");
}

void refuseOptionsTheModeIgnores(const SceneCliOptions& o, bool reference, int spp, int bounces,
                                 float noise) {
  if (reference) {
    for (const char* option :
         {"--probes", "--volume", "--force", "--no-parallax", "--no-distance-roughness", "--ao",
          "--ssao-radius", "--ssao-quality", "--ssr-quality", "--ssr-thickness",
          "--shadow-map-size", "--shadow-cascades", "--shadow-rays", "--no-dominant",
          "--irradiance", "--area-lights", "--specular-aa"})
      if (given(o, option))
        failUsage(option, "is the split sum's; --mode reference does not read it");
    if (o.ssao == "on")
      failUsage("--ssao", "on is the split sum's; --mode reference traces the occlusion itself");
    if (o.ssr == "on")
      failUsage("--ssr", "on is the split sum's; --mode reference traces the reflections itself");
    if (o.shadows == "none" && bounces > 0)
      failUsage("--shadows", fmt::format("none contradicts --bounces {}: every bounce traces the "
                                         "visibility; add --bounces 0",
                                         bounces));
  } else if (given(o, "--bounces")) {
    failUsage("--bounces",
              "is the reference's; add --mode reference (the split sum does not "
              "trace bounces)");
  }
  if (noise > 0.0f && spp < 16)
    failUsage("--noise", fmt::format("is checked from 16 samples per pixel on; --spp {}{} takes "
                                     "fewer",
                                     spp, given(o, "--spp") ? "" : " (the default)"));
}

void checkSceneOptions(const SceneCliOptions& o) {
  if (!o.bakeDir.empty() && !o.env.empty())
    failUsage("--env", fmt::format("contradicts --bake {}: the bake holds the environment; pass "
                                   "one of them",
                                   o.bakeDir));
  if (!o.env.empty() && isSkySpec(o.env)) parseSkySpec(o.env);
  checkEnvScaleOptions(o.envScale, environmentIsNone(o) ? "--env none" : "");
  parseSize(o.size);
  if (o.scene == "sphere" || o.scene == "grid") {
    parseVec3(o.baseColor, "--base-color");
    attenuationColorOf(o);
  }
  if (o.strict && (o.scene == "sphere" || o.scene == "grid"))
    failUsage("--strict", fmt::format("applies to a glTF scene, not the built-in '{}'", o.scene));
  checkVariantOption(o);
  if (!o.lookFrom.empty()) parsePoint(o.lookFrom, "--look-from");
  if (!o.lookAt.empty()) parsePoint(o.lookAt, "--look-at");
  if (!o.lookFrom.empty() && !o.lookAt.empty() &&
      parsePoint(o.lookFrom, "--look-from") == parsePoint(o.lookAt, "--look-at"))
    failUsage("--look-from", fmt::format("equals --look-at ({}): no view direction", o.lookAt));
  if (parseVec3(o.up, "--up") == glm::vec3(0.0f)) failUsage("--up", "must not be the zero vector");
  if (o.orthoWidth && !(*o.orthoWidth > 0.0f))
    failUsage("--ortho-width", fmt::format("must be positive, not {}", *o.orthoWidth));
  if (o.background != "env") parseVec3(o.background, "--background");
  if (!o.ev100.empty()) parseNumbers(o.ev100, 1, "--ev100");
  if (!o.bloom.empty() && o.bloom != "off") {
    const float ec = parseNumbers(o.bloom, 1, "--bloom")[0];
    if (std::abs(ec) > 30.0f)
      failUsage("--bloom",
                fmt::format("{} stops is beyond any exposure; give -30 to 30 or off", ec));
  }
  if (o.ssao == "on" && o.aoRays > 0)
    failUsage("--ssao", fmt::format("on contradicts --ao {}: the ray-traced occlusion is the "
                                    "screen-space one's reference; pass one of them",
                                    o.aoRays));
  refuseIgnoredSceneOptions(o);
}

LoadedBake loadOrBake(const SceneCliOptions& o, const GlobalOptions& global, bool sheen) {
  LoadedBake out;
  BakeOptions options;
  options.sheen = sheen;
  const std::optional<SheenVisibility> asked =
      o.sheenVisibility.empty() ? std::nullopt : parseSheenVisibility(o.sheenVisibility);
  if (asked) options.sheenVisibility = *asked;
  EnvironmentLighting& lighting = out;
  if (!o.bakeDir.empty()) {
    lighting = readEnvironmentLighting(o.bakeDir, options);
    if (asked && out.bake.sheenDfg && *asked != out.options.sheenVisibility)
      failUsage("--sheen-visibility",
                fmt::format("{} contradicts --bake {}, whose sheen table (sheen_dfg.ktx2) was "
                            "integrated with the {} visibility; leave the option out or bake again "
                            "with --sheen-visibility {}",
                            o.sheenVisibility, o.bakeDir,
                            sheenVisibilityName(out.options.sheenVisibility), o.sheenVisibility));
    if (o.envScale.given()) {
      // The bake's radiance scaled as the environment would have been: its source cube (level
      // 0) and sun give the illuminance --env-illuminance measures.
      out.envScale = envScaleFor(o.envScale, horizontalIlluminance(lighting), o.bakeDir);
      scaleEnvironmentLighting(lighting, out.envScale.factor,
                               fmt::format("{}: {}", o.bakeDir, out.envScale.option));
      if (!global.quiet)
        fmt::print(stderr,
                   "ibl: note: {}: the bake's radiance scaled by {:.6g} ({}: {:.6g} lx -> {:.6g} "
                   "lx on an upward surface{})\n",
                   o.bakeDir, out.envScale.factor, out.envScale.option, out.envScale.measuredLux,
                   out.envScale.measuredLux * out.envScale.factor,
                   out.lights.empty() ? "" : ", the sun included");
    }
    return out;
  }
  options.dfgSamples = 256;
  if (environmentIsNone(o)) {
    lighting = unlitEnvironmentLighting(options);
    return out;
  }
  SourceEnvironment env = o.envPixels ? sourceFromImage(*o.envPixels, o.env, {}, false, global)
                                      : loadSourceEnvironment(o.env, {}, false, global);
  requireLight(env.loaded.environment, env.name);
  out.envScale = scaleSourceEnvironment(env, o.envScale, global);
  lighting = bakeEnvironmentLighting(env.loaded.environment, env.lights, options);
  return out;
}

namespace {

// Refuses an image (by its first bytes, or its name) where `what` goes, before a JSON parser
// reads it; `hint` says where the image goes instead.
void refuseImageAs(const std::string& path, std::string_view what, std::string_view hint) {
  std::vector<std::uint8_t> head(64);
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  std::optional<FileFormat> format = detectFileFormat(head);
  if (!format) format = fileFormatFromExtension(path);
  if (format)
    failUsage(path,
              fmt::format("is an image ({}), not {}; {}", fileFormatName(*format), what, hint));
}

}  // namespace

std::vector<std::filesystem::path> sceneInputFiles(const SceneCliOptions& o) {
  std::vector<std::filesystem::path> files;
  const auto add = [&](const std::string& input) {
    requireReadable(input);
    for (auto& f : filesOfInput(input)) files.push_back(std::move(f));
  };
  if (o.scene != "sphere" && o.scene != "grid" && !o.scene.empty()) {
    add(o.scene);
    refuseImageAs(o.scene, "a scene (glTF)",
                  fmt::format("light a scene with it: sphere --env {} (or a glTF file)", o.scene));
  }
  if (!o.env.empty() && !environmentIsNone(o) && !o.envPixels) add(o.env);
  if (!o.lightsFile.empty()) {
    add(o.lightsFile);
    refuseImageAs(o.lightsFile, "a lights file (JSON, docs/lights.md)",
                  fmt::format("an environment goes with --env {}", o.lightsFile));
  }
  std::vector<std::string> dirs = o.probes;
  if (!o.bakeDir.empty()) dirs.push_back(o.bakeDir);
  if (!o.volume.empty()) dirs.push_back(o.volume);
  for (const std::string& dir : dirs) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) fail(dir, "no such directory");
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir, ec))
      if (entry.is_regular_file(ec)) files.push_back(entry.path());
  }
  return files;
}

CameraChoice cameraChoice(const SceneCliOptions& o) {
  CameraChoice choice;
  choice.perspective = o.camera == "perspective";
  choice.yfovDegrees = o.fov;
  choice.orthoWidth = o.orthoWidth;
  if (!o.lookFrom.empty()) choice.from = parsePoint(o.lookFrom, "--look-from");
  if (!o.lookAt.empty()) choice.at = parsePoint(o.lookAt, "--look-at");
  choice.up = parseVec3(o.up, "--up");
  return choice;
}

Camera frameCamera(const SceneCliOptions& o, const Scene& scene, int width, int height) {
  const CameraChoice choice = cameraChoice(o);
  const bool ownCamera = usesSceneCamera(scene, choice);
  if (ownCamera)
    for (const char* option : {"--camera", "--fov", "--up"})
      if (given(o, option))
        failUsage(option, fmt::format("has no effect: {}'s own camera frames the view; add "
                                      "--look-from (or --look-at) to place one with {}",
                                      o.scene, option));
  const Camera camera = ibl::frameCamera(scene, width, height, choice);
  if (!ownCamera && camera.from == camera.at)
    failUsage("--look-from", fmt::format("equals --look-at ({}, {}, {}): no view direction",
                                         camera.at.x, camera.at.y, camera.at.z));
  if (!ownCamera && camera.up == glm::vec3(0.0f)) failUsage("--up", "must not be the zero vector");
  if (o.orthoWidth) {
    if (!(*o.orthoWidth > 0.0f) || !std::isfinite(*o.orthoWidth))
      failUsage("--ortho-width", fmt::format("must be positive, not {}", *o.orthoWidth));
    if (camera.perspective)  // --camera perspective, or the scene's own perspective camera
      failUsage("--ortho-width",
                "applies to an orthographic camera; this view's is perspective "
                "(--camera ortho, or --fov for its angle)");
  }
  checkCamera(camera);
  return camera;
}

bool screenAmbientOcclusionOn(const SceneCliOptions& o) {
  if (!o.ssao.empty()) return o.ssao == "on";
  return o.scene != "sphere" && o.scene != "grid" && o.aoRays == 0;
}

bool screenReflectionsOn(const SceneCliOptions& o) {
  if (!o.ssr.empty()) return o.ssr == "on";
  return o.scene != "sphere" && o.scene != "grid";
}

ShadowMode realTimeShadowMode(const SceneCliOptions& o) {
  if (o.shadows == "none") return ShadowMode::None;
  if (o.shadows == "ray") return ShadowMode::Ray;
  return ShadowMode::Map;
}

RenderOptions shadingOptions(const SceneCliOptions& o, const LoadedBake& baked) {
  RenderOptions r;
  r.sheenVisibility = baked.options.sheenVisibility;
  r.diffuse = o.diffuse == "lambert" ? DiffuseModel::Lambert : DiffuseModel::Disney;
  r.only = o.only == "diffuse"    ? ShadingTerms::Diffuse
           : o.only == "specular" ? ShadingTerms::Specular
           : o.only == "sheen"    ? ShadingTerms::Sheen
                                  : ShadingTerms::Both;
  r.multipleScattering = multipleScatteringChoice(o);
  r.specularMicroOcclusion = o.specularMicroOcclusion;
  r.specularAntialiasing = o.specularAa == "on";
  r.parallaxCorrection = !o.noParallax;
  r.distanceRoughness = !o.noDistanceRoughness;
  r.aoRays = o.aoRays;
  r.screenAmbientOcclusion.enabled = screenAmbientOcclusionOn(o);
  r.screenAmbientOcclusion.radius = o.ssaoRadius;
  r.screenAmbientOcclusion.quality = o.ssaoQuality == "low"    ? AmbientOcclusionQuality::Low
                                     : o.ssaoQuality == "high" ? AmbientOcclusionQuality::High
                                                               : AmbientOcclusionQuality::Medium;
  r.screenReflections.enabled = screenReflectionsOn(o);
  r.screenReflections.thickness = o.ssrThickness;
  r.screenReflections.quality = o.ssrQuality == "low"    ? ReflectionQuality::Low
                                : o.ssrQuality == "high" ? ReflectionQuality::High
                                                         : ReflectionQuality::Medium;
  r.realTimeShadows = realTimeShadowMode(o);
  r.shadowSettings.mapSize = o.shadowMapSize;
  r.shadowSettings.cascades = o.shadowCascades;
  r.shadowSettings.raySamples = o.shadowRays;
  r.dominantDirections = !o.noDominant;
  r.irradiance = o.irradiance == "sh" ? IrradianceSource::Sh : IrradianceSource::Cube;
  r.areaLights = o.areaLights == "frostbite" ? AreaLightModel::Frostbite : AreaLightModel::Ltc;
  r.environmentLight = !environmentIsNone(o);
  if (!r.environmentLight) r.backgroundEnvironment = false;
  if (o.background != "env") {
    r.backgroundEnvironment = false;
    r.backgroundColor = parseVec3(o.background, "--background");
  }
  return r;
}

std::optional<float> bloomCompensation(const SceneCliOptions& o, std::optional<float> otherwise) {
  if (o.bloom == "off") return std::nullopt;
  if (o.bloom.empty()) return otherwise;
  return parseNumbers(o.bloom, 1, "--bloom")[0];
}

float chooseEv100(const SceneCliOptions& o, const Image& linear) {
  if (!o.ev100.empty()) return parseNumbers(o.ev100, 1, "--ev100")[0];
  if (o.aperture > 0.0f && o.shutter > 0.0f && o.iso > 0.0f)
    return ev100FromSettings(o.aperture, o.shutter, o.iso);
  return ev100FromAverageLuminance(averageLogLuminance(linear));
}

ToneMap toneCurve(const SceneCliOptions& o) {
  return o.tonemap == "none"     ? ToneMap::None
         : o.tonemap == "filmic" ? ToneMap::Filmic
                                 : ToneMap::Aces;
}

void checkRenderedImagePath(const std::string& path) {
  const auto format = fileFormatFromExtension(path);
  if (format != FileFormat::Exr && format != FileFormat::Png)
    failUsage(path, "output must be .exr or .png");
}

void writeRenderedImage(const std::string& path, const RenderResult& result, float ev100,
                        ToneMap curve, bool exrExposed) {
  checkRenderedImagePath(path);
  const float exposure = exposureFromEv100(ev100);
  Image exposed(result.color.width, result.color.height);
  for (std::size_t i = 0; i < exposed.pixels.size(); ++i)
    exposed.pixels[i] = toneMap(result.color.pixels[i] * exposure, curve);
  if (fileFormatFromExtension(path) == FileFormat::Exr)
    writeFileAtomic(
        path, encodeExr(exrExposed ? exposed : result.color, ExrPixelType::Float, &result.alpha));
  else
    writeFileAtomic(path, encodePng(exposed));
}

}  // namespace ibl::cli
