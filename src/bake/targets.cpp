// The engine targets' files (docs/targets.md): Filament (cmgen --deploy), the glTF Sample
// Viewer (glTF-IBL-Sampler's outputs), DDS, Babylon.js (.env).
#include "ibl/bake/targets.hpp"

#include <algorithm>
#include <bit>
#include <memory>
#include <numbers>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/env/export.hpp"
#include "ibl/io/babylon_env.hpp"
#include "ibl/io/dds.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/ktx1.hpp"
#include "ibl/io/ktx2.hpp"
#include "output_plan.hpp"

namespace ibl {

std::string_view targetName(EngineTarget t) {
  switch (t) {
    case EngineTarget::Ibl:
      return "ibl";
    case EngineTarget::Filament:
      return "filament";
    case EngineTarget::GltfSampleViewer:
      return "gltf-sample-viewer";
    case EngineTarget::Dds:
      return "dds";
    case EngineTarget::Babylon:
      return "babylon";
  }
  return "?";
}

std::optional<EngineTarget> parseEngineTarget(std::string_view name) {
  for (EngineTarget t : kEngineTargets)
    if (targetName(t) == name) return t;
  return std::nullopt;
}

namespace {

// What a target writes in place of a choice it does not take (every other pair takes it).
struct FixedSetting {
  EngineTarget target;
  BakeSetting setting;
  std::string_view writes;
};
using T = EngineTarget;
using S = BakeSetting;
constexpr std::string_view kCmgenChain = "cmgen's chain (down to 16^2, lod = sqrt(r) (levels - 1))";
constexpr std::string_view kBabylonChain =
    "Babylon's chain (every level down to 1^2, lod = 0.8 log2(width r^2))";
constexpr std::string_view kDdsFiles =
    "DDS files of the specular, irradiance and skybox cubes and the DFG table only";
constexpr FixedSetting kFixedSettings[] = {
    {T::Filament, S::Format, "its fixed R11F_G11F_B10F KTX1 files (cmgen's)"},
    {T::Filament, S::Levels, kCmgenChain},
    {T::Filament, S::Mapping, kCmgenChain},
    {T::Filament, S::IrradianceSize, "irradiance as SH9 only (sh.txt and the KTX's sh key)"},
    {T::Filament, S::DfgTable, "no DFG table (Filament has its own)"},
    {T::Filament, S::FileCopies, "cmgen's files only"},
    {T::Filament, S::Previews, "cmgen's files only"},
    {T::Filament, S::FresnelWeighted, "cmgen's files only"},
    {T::Filament, S::Sheen, "cmgen's files only"},
    {T::GltfSampleViewer, S::FileCopies, "glTF-IBL-Sampler's files only"},
    {T::GltfSampleViewer, S::Previews, "glTF-IBL-Sampler's files only"},
    {T::GltfSampleViewer, S::FresnelWeighted, "glTF-IBL-Sampler's files only"},
    {T::GltfSampleViewer, S::ShWindow, "glTF-IBL-Sampler's files only"},
    {T::Dds, S::FileCopies, kDdsFiles},
    {T::Dds, S::Previews, kDdsFiles},
    {T::Dds, S::FresnelWeighted, kDdsFiles},
    {T::Dds, S::Sheen, kDdsFiles},
    {T::Dds, S::ShWindow, kDdsFiles},
    {T::Babylon, S::Format, "its fixed RGBD PNG faces (Babylon's .env)"},
    {T::Babylon, S::Levels, kBabylonChain},
    {T::Babylon, S::Mapping, kBabylonChain},
    {T::Babylon, S::IrradianceSize, "irradiance as Babylon's spherical polynomial only"},
    {T::Babylon, S::DfgTable, "no DFG table (Babylon has its own)"},
    {T::Babylon, S::FileCopies, "one .env file only"},
    {T::Babylon, S::Previews, "one .env file only"},
    {T::Babylon, S::FresnelWeighted, "one .env file only"},
    {T::Babylon, S::Sheen, "one .env file only"},
};

}  // namespace

std::optional<std::string_view> fixedByTarget(EngineTarget target, BakeSetting setting,
                                              PixelFormat format) {
  // The glTF Sample Viewer's loader reads float cube maps only.
  if (target == T::GltfSampleViewer && setting == S::Format && format != PixelFormat::Rgba16f &&
      format != PixelFormat::Rgba32f)
    return "float cube maps only (rgba16f or rgba32f: the viewer's loader)";
  for (const FixedSetting& f : kFixedSettings)
    if (f.target == target && f.setting == setting) return f.writes;
  return std::nullopt;
}

glm::mat3 filamentOrientation(bool panoramaSource) {
  // Columns are the images of +X, +Y, +Z.
  if (panoramaSource) return {glm::vec3(0, 0, -1), glm::vec3(0, 1, 0), glm::vec3(1, 0, 0)};
  return {glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)};
}

int filamentLevelCount(int size) {
  const int baseExp = std::countr_zero(static_cast<unsigned>(size));
  constexpr int kMinLodExp = 4;  // 16^2
  return baseExp + 1 - (kMinLodExp >= baseExp ? 0 : kMinLodExp);
}

float filamentShPolynomial(int k, glm::vec3 n) {
  const float x = n.x, y = n.y, z = n.z;
  switch (k) {
    case 0:
      return 1.0f;
    case 1:
      return y;
    case 2:
      return z;
    case 3:
      return x;
    case 4:
      return y * x;
    case 5:
      return y * z;
    case 6:
      return 3.0f * z * z - 1.0f;
    case 7:
      return z * x;
    default:
      return x * x - y * y;
  }
}

Sh9 filamentIrradianceSh(const Sh9& radiance) {
  // Our basis function k is a constant times Filament's polynomial k (the same order and the
  // same polynomials, Ramamoorthi & Hanrahan's normalization): read the constant off at a
  // direction where no polynomial vanishes.
  const glm::vec3 d = glm::normalize(glm::vec3(0.3f, 0.5f, 0.8f));
  Sh9 c;
  for (int k = 0; k < 9; ++k) {
    const float norm = shBasis(k, d) / filamentShPolynomial(k, d);
    c[k] = radiance[k] * (norm * shCosineLobe(shBand(k)) / std::numbers::pi_v<float>);
  }
  return c;
}

std::string filamentShText(const Sh9& c) {
  std::string text;
  int k = 0;
  for (int l = 0; l < 3; ++l)
    for (int m = -l; m <= l; ++m, ++k)
      text +=
          fmt::format("({:18.15f}, {:18.15f}, {:18.15f}); // L{}{}, irradiance, pre-scaled base\n",
                      c[k].x, c[k].y, c[k].z, l, m);
  return text;
}

glm::mat3 babylonOrientation(bool panoramaSource) {
  if (panoramaSource) return {glm::vec3(0, 0, 1), glm::vec3(0, 1, 0), glm::vec3(1, 0, 0)};
  return glm::mat3(1.0f);
}

std::array<glm::vec3, 9> babylonSphericalPolynomial(const Sh9& c) {
  // Babylon's SH3ylmBasisConstants (with the Condon-Shortley signs) in the order l00, l1-1, l10,
  // l11, l2-2, l2-1, l20, l21, l22: the same order and polynomials as Filament's.
  const double pi = std::numbers::pi;
  const double k[9] = {
      std::sqrt(1 / (4 * pi)),  -std::sqrt(3 / (4 * pi)),  std::sqrt(3 / (4 * pi)),
      -std::sqrt(3 / (4 * pi)), std::sqrt(15 / (4 * pi)),  -std::sqrt(15 / (4 * pi)),
      std::sqrt(5 / (16 * pi)), -std::sqrt(15 / (4 * pi)), std::sqrt(15 / (16 * pi))};
  std::array<glm::dvec3, 9> h;
  for (int i = 0; i < 9; ++i) h[i] = glm::dvec3(c[i]) / k[i];
  // SphericalPolynomial.updateFromHarmonics, its constants as it writes them.
  std::array<glm::dvec3, 9> p;
  p[0] = -1.02333 * h[3];                                      // x
  p[1] = -1.02333 * h[1];                                      // y
  p[2] = 1.02333 * h[2];                                       // z
  p[3] = 0.886277 * h[0] - 0.247708 * h[6] + 0.429043 * h[8];  // xx
  p[4] = 0.886277 * h[0] - 0.247708 * h[6] - 0.429043 * h[8];  // yy
  p[5] = 0.886277 * h[0] + 0.495417 * h[6];                    // zz
  p[6] = -0.858086 * h[5];                                     // yz
  p[7] = -0.858086 * h[7];                                     // zx
  p[8] = 0.858086 * h[4];                                      // xy
  std::array<glm::vec3, 9> out;
  for (int i = 0; i < 9; ++i) out[i] = glm::vec3(p[i] / pi);
  return out;
}

namespace {

using KtxKeyValuesOf = decltype(Ktx1Texture::keyValues);

std::vector<std::vector<Image>> levelsOf(const CubeMap& cube) {
  std::vector<std::vector<Image>> levels;
  for (const auto& level : cube.levels) levels.emplace_back(level.begin(), level.end());
  return levels;
}

Json roughnessJson(const CubeMap& cube, RoughnessMapping mapping, float minimum = 0.0f) {
  Json r = Json::array();
  for (int m = 0; m < cube.levelCount(); ++m)
    r.push_back(std::max(roughnessForLevel(m, cube.levelCount(), mapping), minimum));
  return r;
}

// Filament: <name>_ibl.ktx, <name>_skybox.ktx (KTX1, R11F_G11F_B10F, cmgen's axes), sh.txt.
void addFilament(OutputPlan& plan, const BakeResult& r, const BakeOutputOptions& out,
                 const std::string& dir, const std::string& name, bool panorama) {
  const glm::mat3 m = filamentOrientation(panorama);
  auto ibl = std::make_shared<CubeMap>(permuteCubeAxes(*r.filamentSpecular, m));
  auto skybox = std::make_shared<CubeMap>();
  skybox->levels = {r.source.levels[0]};
  *skybox = permuteCubeAxes(*skybox, m);
  // The SH in cmgen's axes: the source's 64^2 level moved like the cube maps (texels onto
  // texels, so this is the rotated projection exactly), windowed as the ibl set's.
  CubeMap level64;
  level64.levels = {r.source.levels[levelOfSize(r.source, 64)]};
  const Sh9 radiance = projectSh9(permuteCubeAxes(level64, m));
  const Sh9 sh = filamentIrradianceSh(windowSh9(radiance, r.shWindowFactors));
  std::string metadata;
  for (const glm::vec3& c : sh) metadata += fmt::format("{:g} {:g} {:g}\n", c.x, c.y, c.z);

  const std::string iblPath = dir + name + "_ibl.ktx", skyPath = dir + name + "_skybox.ktx";
  const auto orientation =
      panorama ? "cmgen's: texel(d) = ours at (d.z, d.y, -d.x) (equirect source, X mirrored)"
               : "cmgen's: texel(d) = ours at (-d.x, d.y, d.z) (cube source, X mirrored)";
  // A cube map as cmgen writes it: KTX1, R11F_G11F_B10F, the given key/values.
  const auto addKtx1 = [&](const std::string& path, std::shared_ptr<CubeMap> cube, Json entry,
                           KtxKeyValuesOf keyValues) {
    entry["target"] = "filament";
    entry["path"] = path;
    entry["format"] = "ktx";
    entry["pixel_format"] = "r11f_g11f_b10f";
    entry["size"] = {cube->size(), cube->size()};
    entry["faces"] = 6;
    entry["levels"] = cube->levelCount();
    entry["orientation"] = orientation;
    noteRangeLoss(entry, out, path, rangeLoss(*cube, largestValue(PixelFormat::B10G11R11)),
                  "R11F_G11F_B10F", true);
    plan.add(path, [cube, keyValues] {
      return encodeKtx1({PixelFormat::B10G11R11, 6, levelsOf(*cube), keyValues});
    });
    plan.outputs.push_back(entry);
  };
  addKtx1(iblPath, ibl,
          {{"role", "specular"},
           {"mapping", "filament"},
           {"lod_from_roughness", "lod = (L - 1) r (2 - r)"},
           {"roughness", roughnessJson(*ibl, RoughnessMapping::Filament)},
           {"metadata", {{"sh", "irradiance SH, pre-scaled (as sh.txt)"}}}},
          {{"sh", metadata}});
  addKtx1(skyPath, skybox, {{"role", "skybox"}}, {});
  Json coefficients = Json::array();
  for (const glm::vec3& c : sh) coefficients.push_back({c.x, c.y, c.z});
  plan.addText(dir + "sh.txt", filamentShText(sh));
  plan.outputs.push_back({{"role", "sh"},
                          {"target", "filament"},
                          {"path", dir + "sh.txt"},
                          {"format", "text"},
                          {"stores",
                           "E(n) / pi = c0 + c1 y + c2 z + c3 x + c4 yx + c5 yz + "
                           "c6 (3z^2 - 1) + c7 zx + c8 (x^2 - y^2), cmgen's axes"},
                          {"coefficients", coefficients}});
}

// A cube map as KTX2 in the plan.
void addKtx2Cube(OutputPlan& plan, const BakeOutputOptions& out, const std::string& path,
                 const CubeMap& cube, PixelFormat format, Json entry) {
  entry["path"] = path;
  entry["format"] = "ktx2";
  entry["pixel_format"] = std::string(formatName(format));
  entry["vk_format"] = vulkanFormatName(format);
  entry["size"] = {cube.size(), cube.size()};
  entry["faces"] = 6;
  entry["levels"] = cube.levelCount();
  noteRangeLoss(entry, out, path, rangeLoss(cube, largestValue(format)), formatName(format));
  plan.add(path, [&cube, format] { return encodeKtx2(cubeTexture(cube, format)); });
  plan.outputs.push_back(entry);
}

// The glTF Sample Viewer: ggx/specular.ktx2, lambertian/diffuse.ktx2, charlie/sheen.ktx2 and
// the lookup tables, as glTF-IBL-Sampler writes them and glTF-Sample-Environments ships them.
void addGltfSampleViewer(OutputPlan& plan, const BakeResult& r, const BakeOptions& o,
                         const BakeOutputOptions& out, const std::string& dir) {
  // The viewer loads float cube maps: RGBA16F, or RGBA32F when asked.
  const PixelFormat format =
      out.format == PixelFormat::Rgba32f ? PixelFormat::Rgba32f : PixelFormat::Rgba16f;
  const Json lod = "lod = r (mipCount - 1)";
  addKtx2Cube(plan, out, dir + "ggx/specular.ktx2", r.specular, format,
              {{"role", "specular"},
               {"target", "gltf-sample-viewer"},
               {"mapping", "linear"},
               {"lod_from_roughness", lod},
               {"roughness", roughnessJson(r.specular, o.specular.mapping)}});
  addKtx2Cube(plan, out, dir + "lambertian/diffuse.ktx2", r.irradiance, format,
              {{"role", "irradiance"}, {"target", "gltf-sample-viewer"}, {"stores", "E / pi"}});
  addKtx2Cube(plan, out, dir + "charlie/sheen.ktx2", *r.sheen, format,
              {{"role", "sheen"},
               {"target", "gltf-sample-viewer"},
               {"mapping", "linear"},
               {"lod_from_roughness", lod},
               {"roughness", roughnessJson(*r.sheen, o.specular.mapping, kMinSheenRoughness)}});
  // One table with GGX's A, B and the sheen's E, as glTF-IBL-Sampler's outputLUT; the viewer
  // reads .rg of lut_ggx.png, .b of lut_charlie.png and .r of lut_sheen_E.png.
  auto combined = std::make_shared<Image>(r.dfg);
  auto sheenE = std::make_shared<Image>(r.dfg.width, r.dfg.height);
  for (std::size_t i = 0; i < combined->pixels.size(); ++i) {
    const float e = r.sheenDfg->pixels[i].x;
    combined->pixels[i].z = e;
    sheenE->pixels[i] = glm::vec3(e);
  }
  const auto lut = [&](const std::string& file, std::shared_ptr<Image> image, Json channels) {
    plan.add(dir + file, [image] { return encodePngData(*image); });
    plan.outputs.push_back(
        {{"role", "lut"},
         {"target", "gltf-sample-viewer"},
         {"path", dir + file},
         {"format", "png"},
         {"encoding", "8-bit unorm, linear (round(255 v))"},
         {"size", {image->width, image->height}},
         {"u", "n.v = (i + 0.5) / W"},
         {"v", "r = (j + 0.5) / H, row 0 first"},
         {"channels", channels},
         {"sheen_visibility", std::string(sheenVisibilityName(o.sheenVisibility))}});
  };
  lut("lut_ggx.png", combined, {"A", "B", "sheen E"});
  lut("lut_charlie.png", combined, {"A", "B", "sheen E"});
  lut("lut_sheen_E.png", sheenE, {"sheen E", "sheen E", "sheen E"});
}

// DDS: specular.dds, irradiance.dds, skybox.dds (cube maps, mips), dfg.dds (2D).
void addDds(OutputPlan& plan, const BakeResult& r, const BakeOptions& o,
            const BakeOutputOptions& out, const std::string& dir) {
  const PixelFormat format = out.format;
  const auto cube = [&](const std::string& file, const CubeMap& c, Json entry) {
    entry["target"] = "dds";
    entry["path"] = dir + file;
    entry["format"] = "dds";
    entry["pixel_format"] = std::string(formatName(format));
    entry["dxgi_format"] = dxgiFormat(format);
    entry["size"] = {c.size(), c.size()};
    entry["faces"] = 6;
    entry["levels"] = c.levelCount();
    noteRangeLoss(entry, out, dir + file, rangeLoss(c, largestValue(format)), formatName(format));
    plan.add(dir + file, [&c, format] { return encodeDds({format, 6, levelsOf(c)}); });
    plan.outputs.push_back(entry);
  };
  cube("specular.dds", r.specular,
       {{"role", "specular"},
        {"mapping", std::string(mappingName(o.specular.mapping))},
        {"roughness", roughnessJson(r.specular, o.specular.mapping)}});
  cube("irradiance.dds", r.irradiance, {{"role", "irradiance"}, {"stores", "E / pi"}});
  cube("skybox.dds", r.source, {{"role", "source"}});
  plan.add(dir + "dfg.dds", [&r] { return encodeDds({PixelFormat::Rgba16f, 1, {{r.dfg}}}); });
  plan.outputs.push_back({{"role", "dfg"},
                          {"target", "dds"},
                          {"path", dir + "dfg.dds"},
                          {"format", "dds"},
                          {"pixel_format", "rgba16f"},
                          {"dxgi_format", dxgiFormat(PixelFormat::Rgba16f)},
                          {"size", {r.dfg.width, r.dfg.height}},
                          {"channels", {"A", "B", "diffuse"}}});
}

// Babylon.js: <name>.env (RGBD PNG faces of the full chain at Babylon's roughness per level, its
// axes, the irradiance as its spherical polynomial).
void addBabylon(OutputPlan& plan, const BakeResult& r, const BakeOutputOptions& out,
                const std::string& dir, const std::string& name, bool panorama) {
  const glm::mat3 m = babylonOrientation(panorama);
  auto env = std::make_shared<BabylonEnvironment>();
  const CubeMap chain = permuteCubeAxes(*r.babylonSpecular, m);
  env->width = chain.size();
  env->levels = levelsOf(chain);
  CubeMap level64;
  level64.levels = {r.source.levels[levelOfSize(r.source, 64)]};
  const Sh9 radiance = projectSh9(permuteCubeAxes(level64, m));
  env->polynomial =
      babylonSphericalPolynomial(filamentIrradianceSh(windowSh9(radiance, r.shWindowFactors)));
  const std::string path = dir + name + ".env";
  Json polynomial;
  const char* keys[9] = {"x", "y", "z", "xx", "yy", "zz", "yz", "zx", "xy"};
  for (int k = 0; k < 9; ++k)
    polynomial[keys[k]] = {env->polynomial[k].x, env->polynomial[k].y, env->polynomial[k].z};
  Json entry = {{"role", "specular"},
                {"target", "babylon"},
                {"path", path},
                {"format", "env"},
                {"pixel_format", "rgbd8 png"},
                {"size", {chain.size(), chain.size()}},
                {"faces", 6},
                {"levels", chain.levelCount()},
                {"mapping", "babylon"},
                {"lod_from_roughness", "lod = 0.8 log2(width r^2)"},
                {"roughness", roughnessJson(chain, RoughnessMapping::Babylon)},
                {"orientation", panorama ? "Babylon's: texel(d) = ours at (d.z, d.y, d.x) "
                                           "(equirect source, through HDRCubeTexture's faces)"
                                         : "Babylon's: texel(d) = ours at d (cube source)"},
                {"irradiance", "Babylon's SphericalPolynomial (E / pi through its harmonics)"},
                {"polynomial", polynomial}};
  noteRangeLoss(entry, out, path, rangeLoss(chain, glm::vec3(kRgbdMaxRange)), "RGBD", true);
  plan.add(path, [env] { return encodeBabylonEnv(*env); });
  plan.outputs.push_back(entry);
}

}  // namespace

void addTargetOutputs(OutputPlan& plan, const BakeResult& r, const BakeOptions& o,
                      const BakeOutputOptions& out, const std::string& outDirName,
                      bool panoramaSource) {
  const bool alone = o.targets.size() == 1;
  for (EngineTarget t : o.targets) {
    if (t == EngineTarget::Ibl) continue;
    const std::string dir = alone ? std::string() : std::string(targetName(t)) + "/";
    switch (t) {
      case EngineTarget::Filament:
        addFilament(plan, r, out, dir, outDirName, panoramaSource);
        break;
      case EngineTarget::GltfSampleViewer:
        addGltfSampleViewer(plan, r, o, out, dir);
        break;
      case EngineTarget::Dds:
        addDds(plan, r, o, out, dir);
        break;
      case EngineTarget::Babylon:
        addBabylon(plan, r, out, dir, outDirName, panoramaSource);
        break;
      case EngineTarget::Ibl:
        break;
    }
  }
}

}  // namespace ibl
