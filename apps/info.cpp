// `ibl info`: what is in an image file, and what it means as an environment; or what is in a
// glTF scene.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <fmt/core.h>
#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "ibl/core/error.hpp"
#include "ibl/core/stats.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/photometry.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/gltf.hpp"

namespace ibl::cli {

namespace {

struct InfoOptions {
  std::string file;
  std::string inputLayout;
  std::string layer;
  bool json = false;
};

// The file, or the six files of a {face} pattern as one cube map.
DecodedFile readInput(const InfoOptions& o) {
  const DecodeOptions decode{o.layer};
  if (o.file.find("{face}") == std::string::npos && o.inputLayout != "faces")
    return readImageFile(o.file, decode);
  DecodedFile cube;
  cube.levels.resize(1);
  for (int f = 0; f < kFaceCount; ++f) {
    const std::string path = facePath(o.file, f).string();
    DecodedFile d = readImageFile(path, decode);
    const Image& img = d.levels[0][0];
    if (img.width != img.height)
      fail(path, fmt::format("face is {}x{}, not square", img.width, img.height));
    if (f > 0 && img.width != cube.levels[0][0].width) fail(path, "faces differ in size");
    if (f == 0) cube = DecodedFile{d.format, d.channels, d.detail, {{}}, d.layers};
    cube.levels[0].push_back(std::move(d.levels[0][0]));
  }
  return cube;
}

// Statistics of the stored values, before anything is replaced: over the faces of a cube map
// (a cross's padding is not part of the environment), else over the image.
ImageStats statistics(const std::vector<const Image*>& images) {
  ImageStats stats = imageStats(*images[0]);
  double pixels = static_cast<double>(images[0]->pixels.size());
  stats.mean *= pixels;
  for (std::size_t i = 1; i < images.size(); ++i) {
    const ImageStats s = imageStats(*images[i]);
    stats.min = glm::min(stats.min, s.min);
    stats.max = glm::max(stats.max, s.max);
    stats.mean += s.mean * static_cast<double>(images[i]->pixels.size());
    stats.invalid += s.invalid;
    pixels += static_cast<double>(images[i]->pixels.size());
  }
  stats.mean /= pixels;
  return stats;
}

// Whether the file is a glTF scene (.gltf, .glb), by its extension.
bool isGltf(const std::string& file) {
  std::string ext = std::filesystem::path(file).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".gltf" || ext == ".glb";
}

std::string quoted(const std::string& name) {
  return name.empty() ? std::string() : " '" + name + "'";
}

nlohmann::ordered_json vec(glm::vec3 v) {
  return {v.x, v.y, v.z};
}

// `ibl info` of a glTF file: what describeGltf reports, as text or JSON.
void runGltfInfo(const InfoOptions& o) {
  if (!o.inputLayout.empty()) fail("--input-layout", "applies to images, not to glTF scenes");
  if (!o.layer.empty()) fail("--layer", "applies to EXR images, not to glTF scenes");
  const GltfSummary s = describeGltf(o.file);
  if (o.json) {
    nlohmann::ordered_json j;
    j["file"] = o.file;
    j["format"] = s.binary ? "glb" : "gltf";
    j["generator"] = s.generator;
    j["extensions_used"] = s.extensionsUsed;
    j["extensions_required"] = s.extensionsRequired;
    j["scene"] = s.scene >= 0 ? nlohmann::ordered_json(s.scene) : nlohmann::ordered_json(nullptr);
    j["scenes"] = s.scenes;
    j["variants"] = s.variants;
    j["mesh_instances"] = s.meshInstances;
    j["triangles"] = s.triangles;
    j["vertices"] = s.vertices;
    j["bounds"] = s.hasBounds
                      ? nlohmann::ordered_json{{"min", vec(s.boundsMin)}, {"max", vec(s.boundsMax)}}
                      : nlohmann::ordered_json(nullptr);
    const auto index = [](int i) {
      return i >= 0 ? nlohmann::ordered_json(i) : nlohmann::ordered_json(nullptr);
    };
    for (const auto& m : s.meshes)
      j["meshes"].push_back({{"name", m.name},
                             {"primitives", m.primitives},
                             {"triangle_primitives", m.trianglePrimitives},
                             {"triangles", m.triangles},
                             {"vertices", m.vertices},
                             {"instances", m.instances},
                             {"compression", m.compression},
                             {"vertex_colors", m.vertexColors}});
    for (const auto& m : s.materials)
      j["materials"].push_back(
          {{"name", m.name},
           {"base_color", {m.baseColor.x, m.baseColor.y, m.baseColor.z, m.baseColor.w}},
           {"metallic", m.metallic},
           {"roughness", m.roughness},
           {"emissive", vec(m.emissive)},
           {"alpha_mode", m.alphaMode},
           {"double_sided", m.doubleSided},
           {"textures", m.textures},
           {"transformed_slots", m.transformedSlots},
           {"extensions", m.extensions},
           {"unsupported_extensions", m.unsupported},
           {"ior", m.ior},
           {"specular", m.specular},
           {"specular_color", vec(m.specularColor)},
           {"dielectric_f0", vec(m.dielectricF0)},
           {"dielectric_f90", m.dielectricF90},
           {"clearcoat", m.clearcoat},
           {"clearcoat_roughness", m.clearcoatRoughness},
           {"iridescence", m.iridescence},
           {"iridescence_ior", m.iridescenceIor},
           {"iridescence_thickness",
            {m.iridescenceThicknessMinimum, m.iridescenceThicknessMaximum}},
           {"anisotropy", m.anisotropy},
           {"anisotropy_rotation", m.anisotropyRotation},
           {"transmission", m.transmission},
           {"thickness", m.thickness},
           // JSON has no infinity: null for no absorption.
           {"attenuation_distance", std::isfinite(m.attenuationDistance)
                                        ? nlohmann::json(m.attenuationDistance)
                                        : nlohmann::json(nullptr)},
           {"attenuation_color", vec(m.attenuationColor)}});
    for (const auto& t : s.textures)
      j["textures"].push_back({{"image", index(t.image)},
                               {"source", t.source},
                               {"mime_type", t.mimeType},
                               {"width", t.width},
                               {"height", t.height},
                               {"missing", t.problem == "missing"},
                               {"problem", t.problem},
                               {"used", t.used}});
    for (const auto& l : s.lights)
      j["lights"].push_back({{"name", l.name},
                             {"type", l.type},
                             {"intensity", l.intensity},
                             {"unit", l.type == "directional" ? "lx" : "cd"},
                             {"color", vec(l.color)},
                             {"range", l.range},
                             {"inner_cone_angle", l.innerConeAngle},
                             {"outer_cone_angle", l.outerConeAngle},
                             {"instances", l.instances}});
    for (const auto& c : s.cameras)
      j["cameras"].push_back({{"name", c.name},
                              {"type", c.type},
                              {"yfov", c.yfov},
                              {"aspect_ratio", c.aspectRatio},
                              {"xmag", c.xmag},
                              {"ymag", c.ymag},
                              {"znear", c.znear},
                              {"zfar", c.zfar},
                              {"instances", c.instances}});
    for (const auto& n : s.nodes)
      j["nodes"].push_back({{"name", n.name},
                            {"mesh", index(n.mesh)},
                            {"camera", index(n.camera)},
                            {"light", index(n.light)},
                            {"parent", index(n.parent)},
                            {"in_scene", n.inScene}});
    for (const char* key : {"meshes", "materials", "textures", "lights", "cameras", "nodes"})
      if (!j.contains(key)) j[key] = nlohmann::ordered_json::array();
    j["warnings"] = s.warnings;
    fmt::print("{}\n", j.dump(2));
    return;
  }
  const auto list = [](const std::vector<std::string>& v) {
    std::string out;
    for (const auto& x : v) out += (out.empty() ? "" : ", ") + x;
    return out.empty() ? std::string("none") : out;
  };
  const auto plural = [](std::size_t n, std::string word) {
    if (n != 1) word = word == "vertex" ? "vertices" : word + "s";
    return fmt::format("{} {}", n, word);
  };
  fmt::print("file        {}\n", o.file);
  fmt::print("format      glTF 2.0, {}{}\n", s.binary ? "binary (.glb)" : "JSON (.gltf)",
             s.generator.empty() ? "" : ", generator '" + s.generator + "'");
  fmt::print("extensions  used: {}; required: {}\n", list(s.extensionsUsed),
             list(s.extensionsRequired));
  std::size_t inScene = 0;
  for (const auto& n : s.nodes) inScene += n.inScene;
  if (s.scene >= 0)
    fmt::print("scene       {} of {} ({} in it)\n", s.scene, s.scenes, plural(inScene, "node"));
  else
    fmt::print("scene       none in the file: its root nodes ({} in all)\n",
               plural(inScene, "node"));
  fmt::print("geometry    {}: {}, {}\n", plural(s.meshInstances, "mesh instance"),
             plural(s.triangles, "triangle"), plural(s.vertices, "vertex"));
  if (s.hasBounds)
    fmt::print("bounds      min {:.6g} {:.6g} {:.6g}, max {:.6g} {:.6g} {:.6g} (world space)\n",
               s.boundsMin.x, s.boundsMin.y, s.boundsMin.z, s.boundsMax.x, s.boundsMax.y,
               s.boundsMax.z);
  else
    fmt::print("bounds      none (no triangles in the scene)\n");
  fmt::print("meshes      {}\n", s.meshes.size());
  for (std::size_t i = 0; i < s.meshes.size(); ++i) {
    const auto& m = s.meshes[i];
    fmt::print("  {}{}: {} ({}), {}, {} each; {}{}{}\n", i, quoted(m.name),
               plural(m.primitives, "primitive"), plural(m.trianglePrimitives, "triangle list"),
               plural(m.triangles, "triangle"), plural(m.vertices, "vertex"),
               plural(m.instances, "instance"), m.vertexColors ? "; vertex colors (COLOR_0)" : "",
               m.compression.empty() ? "" : "; " + list(m.compression));
  }
  fmt::print("materials   {}\n", s.materials.size());
  for (std::size_t i = 0; i < s.materials.size(); ++i) {
    const auto& m = s.materials[i];
    std::string extensions;
    for (const auto& e : m.extensions) {
      const bool unsupported =
          std::find(m.unsupported.begin(), m.unsupported.end(), e) != m.unsupported.end();
      extensions += (extensions.empty() ? "" : ", ") + e + (unsupported ? " (not rendered)" : "");
    }
    std::string textures;
    for (int t : m.textures) textures += (textures.empty() ? "" : " ") + std::to_string(t);
    if (!m.transformedSlots.empty())
      textures += " (KHR_texture_transform on " + list(m.transformedSlots) + ")";
    // The dielectric's Fresnel, where KHR_materials_ior or _specular changes it.
    const std::string dielectric =
        m.ior == 1.5f && m.specular == 1.0f && m.specularColor == glm::vec3(1.0f)
            ? ""
            : fmt::format(
                  ", dielectric F0 {:.4g} {:.4g} {:.4g} F90 {:.4g} (ior {:.4g}, "
                  "specular {:.4g}, specular color {:.4g} {:.4g} {:.4g})",
                  m.dielectricF0.x, m.dielectricF0.y, m.dielectricF0.z, m.dielectricF90, m.ior,
                  m.specular, m.specularColor.x, m.specularColor.y, m.specularColor.z);
    const std::string coat = m.clearcoat > 0.0f
                                 ? fmt::format(", clear coat {:.4g} (roughness {:.4g})",
                                               m.clearcoat, m.clearcoatRoughness)
                                 : "";
    const std::string film =
        m.iridescence > 0.0f
            ? fmt::format(", iridescence {:.4g} (film ior {:.4g}, {:.4g} to {:.4g} nm)",
                          m.iridescence, m.iridescenceIor, m.iridescenceThicknessMinimum,
                          m.iridescenceThicknessMaximum)
            : "";
    const std::string anisotropy = m.anisotropy > 0.0f
                                       ? fmt::format(", anisotropy {:.4g} (rotation {:.4g} rad)",
                                                     m.anisotropy, m.anisotropyRotation)
                                       : "";
    std::string transmission =
        m.transmission > 0.0f ? fmt::format(", transmission {:.4g}", m.transmission) : "";
    if (m.transmission > 0.0f && m.thickness > 0.0f)
      transmission += fmt::format(
          " (volume: thickness {:.4g}, attenuation {:.4g} {:.4g} {:.4g} "
          "after {:.4g})",
          m.thickness, m.attenuationColor.x, m.attenuationColor.y, m.attenuationColor.z,
          m.attenuationDistance);
    fmt::print(
        "  {}{}: base color {:.4g} {:.4g} {:.4g} {:.4g}, metallic {:.4g}, roughness "
        "{:.4g}{}{}{}{}{}, emissive {:.4g} {:.4g} {:.4g}, {}{}{}{}\n",
        i, quoted(m.name), m.baseColor.x, m.baseColor.y, m.baseColor.z, m.baseColor.w, m.metallic,
        m.roughness, dielectric, coat, film, anisotropy, transmission, m.emissive.x, m.emissive.y,
        m.emissive.z, m.alphaMode, m.doubleSided ? ", double-sided" : "",
        textures.empty() ? "" : ", textures " + textures,
        extensions.empty() ? "" : "; extensions: " + extensions);
  }
  if (!s.variants.empty())
    fmt::print("variants    {} (KHR_materials_variants; render one with --variant NAME)\n",
               list(s.variants));
  fmt::print("textures    {}\n", s.textures.size());
  for (std::size_t i = 0; i < s.textures.size(); ++i) {
    const auto& t = s.textures[i];
    const std::string image =
        t.image >= 0 ? fmt::format("image {} ({})", t.image, t.source) : std::string("no image");
    const std::string state = t.problem == "missing" ? "MISSING"
                              : !t.problem.empty()   ? "UNREADABLE: " + t.problem
                                                     : fmt::format("{}x{}", t.width, t.height);
    fmt::print("  {}: {} {}{}\n", i, image, state, t.used ? "" : " (no material reads it)");
  }
  fmt::print("lights      {}\n", s.lights.size());
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const auto& l = s.lights[i];
    fmt::print("  {}{}: {}, {:.6g} {}, color {:.4g} {:.4g} {:.4g}{}; {}\n", i, quoted(l.name),
               l.type, l.intensity, l.type == "directional" ? "lx" : "cd", l.color.x, l.color.y,
               l.color.z, l.range > 0.0 ? fmt::format(", range {:.6g}", l.range) : "",
               plural(l.instances, "instance"));
  }
  fmt::print("cameras     {}\n", s.cameras.size());
  for (std::size_t i = 0; i < s.cameras.size(); ++i) {
    const auto& c = s.cameras[i];
    if (c.type == "orthographic")
      fmt::print("  {}{}: orthographic, xmag {:.6g}, ymag {:.6g}; {}\n", i, quoted(c.name), c.xmag,
                 c.ymag, plural(c.instances, "instance"));
    else
      fmt::print("  {}{}: perspective, vertical field of view {:.4g} degrees; {}\n", i,
                 quoted(c.name), c.yfov * 180.0 / 3.14159265358979323846,
                 plural(c.instances, "instance"));
  }
  fmt::print("nodes       {}\n", s.nodes.size());
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    const auto& n = s.nodes[i];
    std::string what;
    const auto add = [&](const std::string& x) { what += (what.empty() ? "" : ", ") + x; };
    if (n.mesh >= 0)
      add(fmt::format("mesh {}{}", n.mesh,
                      quoted(s.meshes[static_cast<std::size_t>(n.mesh)].name)));
    if (n.camera >= 0) add(fmt::format("camera {}", n.camera));
    if (n.light >= 0) add(fmt::format("light {}", n.light));
    if (n.parent >= 0) add(fmt::format("child of {}", n.parent));
    if (!n.inScene) add("not in the scene");
    fmt::print("  {}{}{}{}\n", i, quoted(n.name), what.empty() ? "" : ": ", what);
  }
  if (!s.warnings.empty()) {
    fmt::print("warnings    {}\n", s.warnings.size());
    for (const auto& w : s.warnings) fmt::print("  {}\n", w);
  }
}

void runInfo(const InfoOptions& o) {
  if (isGltf(o.file)) {
    runGltfInfo(o);
    return;
  }
  DecodedFile d = readInput(o);
  const Image& base = d.levels[0][0];
  const int faces = static_cast<int>(d.levels[0].size());
  const int levels = static_cast<int>(d.levels.size());
  const std::string format(fileFormatName(d.format));
  const int channels = d.channels;
  const std::string detail = d.detail;
  const std::vector<std::string> layers = d.layers;
  const int width = base.width, height = base.height;

  std::optional<Environment> env;
  std::optional<Layout> layout;
  if (!o.inputLayout.empty() && o.inputLayout != "faces") layout = parseLayout(o.inputLayout);
  std::vector<const Image*> images;
  if (faces == kFaceCount || layout || layoutFromShape(base.width, base.height)) {
    env = environmentFromFile(std::move(d), {layout, o.layer}, o.file);
    if (o.file.find("{face}") != std::string::npos || o.inputLayout == "faces")
      env->layout = Layout::Faces;
    if (env->isCube()) {
      for (const Image& face : env->cube.levels[0]) images.push_back(&face);
    } else {
      images.push_back(&env->equirect);
    }
  } else {
    images.push_back(&d.levels[0][0]);
  }
  const ImageStats stats = statistics(images);
  // Damaged pixels as stored, before NaN, infinities and negative values are replaced.
  PixelDamage damage;
  if (env) {
    damage = findPixelDamage(*env);
    sanitizeEnvironment(*env);
  } else {
    const Image& image = *images[0];
    damage.regions = damagedRegions(damagedPixelMask(image), image.width, image.height, 0);
  }
  const bool cube = env && env->isCube();

  nlohmann::ordered_json j;
  j["file"] = o.file;
  j["format"] = format;
  j["detail"] = detail;
  j["channels"] = channels;
  if (format == "exr") j["layers"] = layers;
  j["width"] = width;
  j["height"] = height;
  j["faces"] = faces;
  j["levels"] = levels;
  j["layout"] = env ? std::string(layoutName(env->layout)) : "2d";
  j["min"] = {stats.min.x, stats.min.y, stats.min.z};
  j["max"] = {stats.max.x, stats.max.y, stats.max.z};
  j["mean"] = {stats.mean.x, stats.mean.y, stats.mean.z};
  j["nan"] = stats.invalid.nan;
  j["infinite"] = stats.invalid.infinite;
  j["negative"] = stats.invalid.negative;
  j["damaged"] = {{"pixels", damage.pixels()}, {"regions", nlohmann::ordered_json::array()}};
  for (const DamagedRegion& r : damage.regions)
    j["damaged"]["regions"].push_back({{"face", r.face},
                                       {"x0", r.x0},
                                       {"y0", r.y0},
                                       {"x1", r.x1},
                                       {"y1", r.y1},
                                       {"pixels", r.pixels}});
  glm::dvec3 integral(0.0);
  std::optional<glm::vec3> brightest;
  double illuminance = 0.0;
  LuminanceRange nits;
  if (env) {
    // Photometry, the values taken as nits (cd/m^2): lux on an upward (+Y) surface, and the
    // luminance over the directions.
    illuminance = horizontalIlluminance(*env);
    nits = luminanceRange(*env);
    j["horizontal_illuminance"] = illuminance;
    j["luminance"] = {
        {"min", nits.min}, {"max", nits.max}, {"median", nits.median}, {"mean", nits.mean}};
    integral = radiantIntegral(*env);
    brightest = brightestDirection(*env);
    j["radiant_integral"] = {integral.x, integral.y, integral.z};
    j["radiant_integral_luminance"] = luminance(glm::vec3(integral));
    j["brightest_direction"] =
        brightest ? nlohmann::ordered_json{brightest->x, brightest->y, brightest->z}
                  : nlohmann::ordered_json(nullptr);
  }
  if (o.json) {
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("file        {}\n", o.file);
  fmt::print("format      {} ({}), {} channel{}\n", format, detail, channels,
             channels == 1 ? "" : "s");
  if (layers.size() > 1 || (layers.size() == 1 && !layers[0].empty())) {
    std::string list;
    for (const auto& l : layers) list += (list.empty() ? "" : ", ") + (l.empty() ? "(plain)" : l);
    fmt::print("layers      {}\n", list);
  }
  fmt::print("layout      {}\n", env ? layoutName(env->layout) : "2d image (not an environment)");
  fmt::print("size        {}x{}{}, {} level{}\n", width, height,
             faces == kFaceCount ? " per face" : "", levels, levels == 1 ? "" : "s");
  fmt::print("min         {:.6g} {:.6g} {:.6g}\n", stats.min.x, stats.min.y, stats.min.z);
  fmt::print("max         {:.6g} {:.6g} {:.6g}\n", stats.max.x, stats.max.y, stats.max.z);
  fmt::print("mean        {:.6g} {:.6g} {:.6g}\n", stats.mean.x, stats.mean.y, stats.mean.z);
  fmt::print("invalid     {} NaN, {} infinite, {} negative components\n", stats.invalid.nan,
             stats.invalid.infinite, stats.invalid.negative);
  if (damage.empty())
    fmt::print("damaged     none\n");
  else
    fmt::print(
        "damaged     {}: channels that contradict their neighbourhood by orders of magnitude "
        "(`ibl convert --repair-damage` replaces them)\n",
        damageSummary(damage, cube));
  if (env) {
    fmt::print(
        "integral    {:.6g} {:.6g} {:.6g}  (RGB, sum of L dw over the sphere; invalid "
        "values as 0)\n",
        integral.x, integral.y, integral.z);
    if (brightest)
      fmt::print("brightest   direction {:.3f} {:.3f} {:.3f}\n", brightest->x, brightest->y,
                 brightest->z);
    else
      fmt::print("brightest   none (no pixel has a positive luminance)\n");
    fmt::print("illuminance {:.6g} lx on an upward (+Y) surface, the values taken as nits\n",
               illuminance);
    fmt::print(
        "luminance   min {:.6g}, median {:.6g}, mean {:.6g}, max {:.6g} nits (Rec. 709 Y; "
        "median and mean over the sphere's directions)\n",
        nits.min, nits.median, nits.mean, nits.max);
  }
}

}  // namespace

void addInfoCommand(CLI::App& app, const GlobalOptions&) {
  auto opts = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand("info",
                                     "Describe an image file (format, layout, size, "
                                     "value range, invalid pixels, radiant integral, horizontal "
                                     "illuminance and luminance in nits) or a glTF "
                                     "scene (meshes, materials, textures, lights, cameras, "
                                     "bounds, names)");
  cmd->add_option("file", opts->file,
                  "Image file (.hdr, .exr, .png, .jpg, .ktx2; a path with {face} names six face "
                  "files) or glTF scene (.gltf, .glb)")
      ->required();
  cmd->add_option("--input-layout", opts->inputLayout, "Layout (default: from the shape)")
      ->check(CLI::IsMember({"equirect", "cross", "hcross", "vcross", "hstrip", "vstrip", "faces",
                             "mirrorball", "angular"}));
  cmd->add_option("--layer", opts->layer, "EXR layer to describe (default: as `ibl convert`)");
  cmd->add_flag("--json", opts->json, "Print JSON instead of text");
  cmd->callback([opts] { runInfo(*opts); });
}

}  // namespace ibl::cli
