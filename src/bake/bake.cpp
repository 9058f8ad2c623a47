#include "ibl/bake/bake.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <system_error>

#include <fmt/format.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "ibl/bake/dfg.hpp"
#include "ibl/bake/preview.hpp"
#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/core/version.hpp"
#include "ibl/env/export.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/json_file.hpp"
#include "ibl/io/ktx2.hpp"
#include "output_plan.hpp"

namespace ibl {

namespace fs = std::filesystem;

constexpr int kPreviewColumns = 6;

namespace {

// Times the bake's stages into one map; stages run on several threads at once (the DFG table
// beside the convolutions), so the map is written under a lock.
class StageTimer {
 public:
  explicit StageTimer(std::map<std::string, double>& timings) : timings_(timings) {}
  template <typename F>
  auto operator()(const std::string& stage, F&& f) {
    const auto start = std::chrono::steady_clock::now();
    auto result = f();
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const std::lock_guard lock(mutex_);
    timings_[stage] = ms;
    return result;
  }

 private:
  std::map<std::string, double>& timings_;
  std::mutex mutex_;
};

}  // namespace

// Records in a manifest entry, and warns, what a format's range clamps of an output.
void noteRangeLoss(Json& entry, const BakeOutputOptions& out, const std::string& file,
                   const RangeLoss& loss, std::string_view format, bool engineFormat) {
  if (loss.clamped == 0) return;
  entry["clamped"] = {
      {"values", loss.clamped}, {"brightest", loss.brightest}, {"lost_power", loss.lostPower}};
  if (out.warn)
    out.warn(fmt::format(
        "{}: {} values above the {} range clamped (brightest {:g}), {:.3g} % of "
        "the power of its worst level lost; {}--clamp MAX to choose the limit",
        file, loss.clamped, format, loss.brightest, 100.0 * loss.lostPower,
        engineFormat ? "the engine's format is fixed: " : "bake with --format rgba32f, or "));
}

bool BakeOptions::wants(EngineTarget t) const {
  return std::find(targets.begin(), targets.end(), t) != targets.end();
}

void checkBakeOptions(const BakeOptions& o) {
  if (o.wants(EngineTarget::GltfSampleViewer) && o.specular.mapping != RoughnessMapping::Linear)
    failUsage("--target gltf-sample-viewer",
              fmt::format("the glTF Sample Viewer reads roughness r at lod r (mipCount - 1); bake "
                          "it with --mapping linear, not {}",
                          mappingName(o.specular.mapping)));
}

namespace {

// Texels of a cube map chain of `levels` levels from size n down (all levels when 0 or more
// than there are).
double chainTexels(int n, int levels) {
  double texels = 0.0;
  for (int m = 0; (levels <= 0 || m < levels) && (n >> m) >= 1; ++m)
    texels += 6.0 * static_cast<double>(n >> m) * static_cast<double>(n >> m);
  return texels;
}

int specularLevels(const BakeOptions& o) {
  const int n = o.specular.size;
  if (o.specular.levels > 0) return o.specular.levels;
  return std::max(1, static_cast<int>(std::bit_width(static_cast<unsigned>(n))) - 3);  // to 8^2
}

}  // namespace

std::uint64_t estimateBakeMemoryBytes(const BakeOptions& o, const BakeOutputOptions& out) {
  // Measured peak resident memory, per texel of one level-0 cube (6 n^2), on 256^2 to 2048^2
  // bakes: 82 bytes for the ibl set (source and specular chains, their encodings, the resampling
  // and convolution buffers); each further prefiltered chain (sheen, the Fresnel-weighted pair,
  // Filament's, Babylon's) 27; each further target's encodings about 25; EXR and HDR copies 57;
  // 32-bit floats 10. Rounded up.
  const int chains = (o.wantsSheen() ? 1 : 0) + (o.fresnelWeighted ? 2 : 0) +
                     (o.wants(EngineTarget::Filament) ? 1 : 0) +
                     (o.wants(EngineTarget::Babylon) ? 1 : 0);
  const int targets = static_cast<int>(o.targets.size()) - (o.wants(EngineTarget::Ibl) ? 1 : 0);
  double perTexel = 90.0 + 30.0 * chains + 25.0 * targets;
  if (out.exr || out.hdr) perTexel += 60.0;
  if (out.format == PixelFormat::Rgba32f) perTexel += 12.0;
  const double n = o.specular.size;
  const double irradiance = 6.0 * o.irradianceSize * o.irradianceSize * 48.0;
  const double tables = 2.0 * o.dfgSize * o.dfgSize * 24.0;
  return static_cast<std::uint64_t>(64e6 + perTexel * 6.0 * n * n + irradiance + tables);
}

std::uint64_t estimateBakeOutputBytes(const BakeOptions& o, const BakeOutputOptions& out) {
  const int n = o.specular.size;
  const double texel = bytesPerTexel(out.format);
  const double specular = chainTexels(n, specularLevels(o)), source = chainTexels(n, 0);
  const double irradiance = 6.0 * o.irradianceSize * o.irradianceSize;
  const double table = static_cast<double>(o.dfgSize) * o.dfgSize * 8.0;
  double bytes = 1e6;  // manifest, SH, previews
  if (o.wants(EngineTarget::Ibl)) {
    bytes += texel * (specular * (1 + (o.fresnelWeighted ? 2 : 0) + (o.sheen ? 1 : 0)) + source +
                      irradiance) +
             2.0 * table;
    if (out.exr) bytes += 8.0 * (specular + irradiance + 6.0 * n * n);
    if (out.hdr) bytes += 4.0 * (specular + irradiance + 6.0 * n * n);
  }
  if (o.wants(EngineTarget::Filament))
    bytes += 4.0 * (chainTexels(n, filamentLevelCount(n)) + source);
  if (o.wants(EngineTarget::Babylon)) bytes += 4.0 * source;
  if (o.wants(EngineTarget::Dds)) bytes += texel * (specular + irradiance + source) + table;
  if (o.wants(EngineTarget::GltfSampleViewer))
    bytes += std::max(texel, 8.0) * (2.0 * specular + irradiance) + 3.0 * table;
  return static_cast<std::uint64_t>(bytes);
}

namespace {

// The DFG tables depend on their kind, size and sample count alone: each is integrated once per
// process and copied into every later bake that asks for it (the viewer's time of day bakes again
// for each sun position; a batch bakes many files).
Image oncePerProcess(std::array<int, 3> key, const std::function<Image()>& integrate) {
  static std::mutex mutex;
  static std::map<std::array<int, 3>, Image> tables;
  {
    const std::lock_guard lock(mutex);
    if (const auto it = tables.find(key); it != tables.end()) return it->second;
  }
  Image table = integrate();
  const std::lock_guard lock(mutex);
  tables.emplace(key, table);
  return table;
}

}  // namespace

BakeResult bakeEnvironment(const Environment& env, const BakeOptions& o, const ProgressFn& progress,
                           gpu::Context* device) {
  checkBakeOptions(o);
  BakeResult r;
  if (device) r.device = device->device().name;
  StageTimer time(r.timingsMs);
  const auto start = std::chrono::steady_clock::now();
  const int size = o.specular.size;
  const std::string sourceStage = fmt::format("source cube {}x{} with mips", size, size);
  if (progress) progress(sourceStage, 0.0);
  r.source = time("source", [&] {
    CubeMap cube = env.isCube() && env.cube.size() == size && o.rotateDegrees == 0.0f ? CubeMap()
                   : device ? gpu::resampleToCube(*device, env, size, o.rotateDegrees)
                            : resampleToCube(env, size, o.rotateDegrees);
    if (cube.levels.empty()) cube.levels = {env.cube.levels[0]};
    if (device) {
      gpu::buildMipChain(*device, cube);
    } else {
      buildMipChain(cube);
    }
    return cube;
  });
  if (progress) progress(sourceStage, 1.0);
  // The DFG table does not depend on the environment: compute it beside the convolutions.
  parallelInvoke(
      [&] {
        r.specular = time("specular", [&] {
          return device
                     ? gpu::prefilterGgx(*device, r.source, o.specular, &r.specularLevels, progress)
                     : prefilterGgx(r.source, o.specular, &r.specularLevels, progress);
        });
        // A further chain, its levels reported under its own name.
        const auto prefilter = [&](const PrefilterOptions& chain, const std::string& name) {
          ProgressFn chainProgress;
          if (progress)
            chainProgress = [&](const std::string& stage, double f) {
              progress(name + ": " + stage, f);
            };
          return device ? gpu::prefilterGgx(*device, r.source, chain, nullptr, chainProgress)
                        : prefilterGgx(r.source, chain, nullptr, chainProgress);
        };
        if (o.fresnelWeighted) {
          PrefilterOptions variant = o.specular;
          variant.weight = PrefilterWeight::FresnelF0Zero;
          r.specularF0Zero =
              time("specular_f0_0", [&] { return prefilter(variant, "Fresnel-weighted F0 = 0"); });
          variant.weight = PrefilterWeight::FresnelF0One;
          r.specularF0One =
              time("specular_f0_1", [&] { return prefilter(variant, "Fresnel-weighted F0 = 1"); });
        }
        if (o.wantsSheen()) {
          // The specular chain's levels and mapping, so that one lod serves both lobes.
          PrefilterOptions sheen = o.specular;
          sheen.weight = PrefilterWeight::Charlie;
          sheen.method = PrefilterMethod::Direct;
          r.sheen = time("sheen", [&] { return prefilter(sheen, "sheen (Charlie)"); });
        }
        if (o.wants(EngineTarget::Filament)) {
          PrefilterOptions filament = o.specular;
          filament.levels = filamentLevelCount(o.specular.size);
          filament.mapping = RoughnessMapping::Filament;
          r.filamentSpecular =
              time("filament_specular", [&] { return prefilter(filament, "Filament's chain"); });
        }
        if (o.wants(EngineTarget::Babylon)) {
          PrefilterOptions babylon = o.specular;
          babylon.levels = fullMipCount(o.specular.size);
          babylon.mapping = RoughnessMapping::Babylon;
          r.babylonSpecular =
              time("babylon_specular", [&] { return prefilter(babylon, "Babylon.js's chain"); });
        }
        r.irradiance = time("irradiance", [&] {
          const int level = levelOfSize(r.source, o.irradianceSize);
          if (!device) return convolveIrradiance(r.source, o.irradianceSize, level, progress);
          const std::string stage =
              fmt::format("irradiance {}x{}", o.irradianceSize, o.irradianceSize);
          if (progress) progress(stage, 0.0);
          CubeMap irradiance = gpu::convolveIrradiance(*device, r.source, o.irradianceSize, level);
          if (progress) progress(stage, 1.0);
          return irradiance;
        });
        r.sh = time("sh", [&] {
          // The 64^2 level integrates like level 0 (box-filtered mips keep every texel's
          // integral), and bands 0-2 vary slowly across its texels: 16x less work.
          const int level = levelOfSize(r.source, 64);
          const Sh9 sh =
              device ? gpu::projectSh9(*device, r.source, level) : projectSh9(r.source, level);
          return windowSh9(sh, o.shWindow, &r.shWindowFactors);
        });
      },
      [&] {
        const std::string dfgStage = fmt::format("DFG table {}x{} ({} samples per texel)",
                                                 o.dfgSize, o.dfgSize, o.dfgSamples);
        if (progress) progress(dfgStage, 0.0);
        r.dfg = time("dfg", [&] {
          return device ? gpu::integrateDfgLut(*device, o.dfgSize, o.dfgSize, o.dfgSamples)
                        : oncePerProcess({0, o.dfgSize, o.dfgSamples}, [&] {
                            return integrateDfgLut(o.dfgSize, o.dfgSize, o.dfgSamples, progress,
                                                   dfgStage);
                          });
        });
        if (progress) progress(dfgStage, 1.0);  // also when the table was integrated before
        if (o.wantsSheen()) {
          const std::string sheenStage = fmt::format("sheen table {}x{} ({} samples per texel)",
                                                     o.dfgSize, o.dfgSize, 4 * o.dfgSamples);
          if (progress) progress(sheenStage, 0.0);
          r.sheenDfg = time("sheen_dfg", [&] {
            return oncePerProcess(
                {1 + static_cast<int>(o.sheenVisibility), o.dfgSize, o.dfgSamples}, [&] {
                  return integrateSheenDfgLut(o.dfgSize, o.dfgSize, 4 * o.dfgSamples,
                                              o.sheenVisibility, progress, sheenStage);
                });
          });
          if (progress) progress(sheenStage, 1.0);
        }
      });
  r.timingsMs["total"] =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return r;
}

namespace {

// Numbers that were floats print as the shortest decimal that reads back as the same float
// (0.2, not 0.20000000298023224); true doubles are left alone.
void shortenFloats(Json& j) {
  if (j.is_structured()) {
    for (auto& child : j) shortenFloats(child);
  } else if (j.is_number_float()) {
    const double d = j.get<double>();
    const float f = static_cast<float>(d);
    if (std::isfinite(d) && static_cast<double>(f) == d) j = std::stod(fmt::format("{}", f));
  }
}

Json vec3Json(glm::vec3 v) {
  return Json::array({v.x, v.y, v.z});
}

const char* shWindowName(ShWindow w) {
  switch (w) {
    case ShWindow::Lanczos:
      return "lanczos";
    case ShWindow::Cmgen:
      return "cmgen";
    case ShWindow::Off:
      break;
  }
  return "off";
}

// The manifest's words for the SH window and the band factors it applied.
std::string shWindowText(ShWindow w, const std::array<float, 3>& f) {
  if (w == ShWindow::Off) return "no";
  const std::string factors = fmt::format("({:.3g}, {:.3g}, {:.3g})", f[0], f[1], f[2]);
  return w == ShWindow::Lanczos
             ? "Lanczos sigma factors " + factors
             : "cmgen's auto window, sinc(pi l / w)^4 with the widest w whose irradiance stays "
               ">= 0: factors " +
                   factors;
}

Json conventionsJson(const BakeOptions& o, const BakeResult& r) {
  Json c;
  c["world"] = {{"handedness", "right"}, {"up", "+Y"}};
  c["cubemap"] = {
      {"face_order", {"+X", "-X", "+Y", "-Y", "+Z", "-Z"}},
      {"face_mapping", "Vulkan/OpenGL major-axis table; s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2"},
      {"faces",
       {{"+X", {{"sc", "-z"}, {"tc", "-y"}}},
        {"-X", {{"sc", "+z"}, {"tc", "-y"}}},
        {"+Y", {{"sc", "+x"}, {"tc", "+z"}}},
        {"-Y", {{"sc", "+x"}, {"tc", "-z"}}},
        {"+Z", {{"sc", "+x"}, {"tc", "-y"}}},
        {"-Z", {{"sc", "-x"}, {"tc", "-y"}}}}},
      {"row0", "t = 0"}};
  c["equirect"] = {{"u", "0.5 + atan2(z, x) / (2 pi)"},
                   {"v", "acos(y) / pi"},
                   {"row0", "v = 0 (+Y, straight up)"},
                   {"center", "+X"},
                   {"rotate_degrees", o.rotateDegrees},
                   {"rotation", "R_y(deg), right-handed about +Y: a feature at d appears at R d"}};
  c["roughness"] = {{"parameter", "perceptual roughness r (glTF metallic-roughness)"},
                    {"alpha", "r^2"}};
  Json levels = Json::array();
  for (const auto& l : r.specularLevels) levels.push_back(l.roughness);
  c["specular"] = {
      {"model", "split sum (Karis 2013), n = v = r, GGX with alpha = r^2"},
      {"mapping", std::string(mappingName(o.specular.mapping))},
      {"level_roughness",
       o.specular.mapping == RoughnessMapping::Linear ? "r = m / (L - 1)" : "r = (m / (L - 1))^2"},
      {"lod_from_roughness", o.specular.mapping == RoughnessMapping::Linear
                                 ? "lod = r (L - 1)"
                                 : "lod = sqrt(r) (L - 1)"},
      {"weight", "D(h) (n.l)"},
      {"level0", "mirror reflection: the source itself"},
      {"roughness_per_level", levels}};
  if (o.fresnelWeighted)
    c["specular_fresnel_weighted"] = {
        {"weight", "D(h) V(v, l) F(v.h) (n.l), F0 = 0 and F0 = 1, n = v"},
        {"combine", "specular = LD_1 F0 (A + B) + LD_0 (1 - F0) B"}};
  c["dfg"] = {{"u", "n.v = (i + 0.5) / W"},
              {"v", "r = (j + 0.5) / H"},
              {"row0_first", true},
              {"r", "A: scale of F0 (single scattering, height-correlated Smith)"},
              {"g", "B: bias, times f90"},
              {"b", "renormalized Disney diffuse (Frostbite), integral of Fd / pi (n.l)"},
              {"specular", "prefiltered * (F0 * A + f90 * B)"},
              {"diffuse", "albedo * irradiance * dfg.b"},
              {"multiple_scattering", "specular *= 1 + F0 * (1 / (A + B) - 1)"}};
  c["irradiance"] = {{"stores", "E(n) / pi: the radiance of a white Lambertian surface"},
                     {"constant_environment", "L stays L"}};
  c["sh"] = {
      {"basis", "real spherical harmonics, bands 0..2, Ramamoorthi & Hanrahan 2001 normalization"},
      {"order",
       {"(0,0)", "(1,-1)", "(1,0)", "(1,1)", "(2,-2)", "(2,-1)", "(2,0)", "(2,1)", "(2,2)"}},
      {"functions",
       {"0.282095", "0.488603 y", "0.488603 z", "0.488603 x", "1.092548 x y", "1.092548 y z",
        "0.315392 (3 z^2 - 1)", "1.092548 x z", "0.546274 (x^2 - y^2)"}},
      {"frame", "world (x, y, z), +Y up"},
      {"coefficients", "radiance L_lm = integral of L Y_lm"},
      {"irradiance",
       "E(n) = sum A_l L_lm Y_lm(n), A = (pi, 2 pi / 3, pi / 4); divide by pi for the "
       "irradiance cube's units"},
      {"windowed", shWindowText(o.shWindow, r.shWindowFactors)}};
  c["color"] = {{"primaries", "Rec.709 / sRGB"}, {"encoding", "linear"}};
  return c;
}

// One cube map as flat files (cross or six faces) in `format` (EXR or HDR), level by level.
void addFlatCube(OutputPlan& plan, const Json& entry, const CubeMap& cube, const std::string& stem,
                 FileFormat format, Layout layout) {
  const std::string ext = format == FileFormat::Exr ? ".exr" : ".hdr";
  const auto encoder = [format](const Image& img) {
    return format == FileFormat::Exr ? encodeExr(img, ExrPixelType::Half) : encodeHdr(img);
  };
  for (int m = 0; m < cube.levelCount(); ++m) {
    const std::string base = cube.levelCount() > 1 ? fmt::format("{}_m{}", stem, m) : stem;
    Json e = entry;
    e["format"] = fileFormatName(format);
    e["level"] = m;
    e["size"] = {cube.levels[m][0].width, cube.levels[m][0].width};
    if (layout == Layout::Faces) {
      Json paths = Json::array();
      for (int f = 0; f < kFaceCount; ++f) {
        const std::string p = fmt::format("{}_{}{}", base, kFaceNames[f], ext);
        plan.add(p, [=, &cube] { return encoder(cube.levels[m][f]); });
        paths.push_back(p);
      }
      e["layout"] = "faces";
      e["path"] = paths[0];
      e["paths"] = paths;
    } else {
      const std::string p = base + ext;
      plan.add(p, [=, &cube] { return encoder(flatFromCube(cube, m, layout)); });
      e["layout"] = layoutName(layout);
      if (layout == Layout::Equirect)
        e["size"] = {4 * cube.levels[m][0].width, 2 * cube.levels[m][0].width};
      e["path"] = p;
    }
    plan.outputs.push_back(e);
  }
}

// A cube map as `stem`.ktx2 (all levels) and, if asked, as EXR / HDR files; `extra` joins each
// manifest entry.
void addCube(OutputPlan& plan, const BakeOutputOptions& out, const std::string& role,
             const std::string& stem, const CubeMap& cube, const Json& extra) {
  Json e = {{"role", role},
            {"path", stem + ".ktx2"},
            {"format", "ktx2"},
            {"pixel_format", std::string(formatName(out.format))},
            {"vk_format", vulkanFormatName(out.format)},
            {"size", {cube.size(), cube.size()}},
            {"faces", 6},
            {"levels", cube.levelCount()}};
  if (extra.is_object()) e.update(extra);
  noteRangeLoss(e, out, stem + ".ktx2", rangeLoss(cube, largestValue(out.format)),
                formatName(out.format));
  plan.add(stem + ".ktx2",
           [&cube, format = out.format] { return encodeKtx2(cubeTexture(cube, format)); });
  plan.outputs.push_back(e);
  for (auto [enabled, format] :
       {std::pair{out.exr, FileFormat::Exr}, std::pair{out.hdr, FileFormat::Hdr}})
    if (enabled) {
      Json flat = {{"role", role}};
      if (extra.is_object()) flat.update(extra);
      if (format == FileFormat::Exr)  // half floats (Radiance HDR holds any float)
        noteRangeLoss(flat, out, stem + " (EXR)",
                      rangeLoss(cube, largestValue(PixelFormat::Rgba16f)), "half-float EXR");
      addFlatCube(plan, flat, cube, stem, format, out.layout);
    }
}

// The prefiltered chain (and the Fresnel-weighted pair), with each level's roughness and method.
void addSpecular(OutputPlan& plan, const BakeResult& r, const BakeOptions& o,
                 const BakeOutputOptions& out) {
  Json roughness = Json::array();
  Json methods = Json::array();
  for (const auto& l : r.specularLevels) {
    roughness.push_back(l.roughness);
    methods.push_back({{"roughness", l.roughness},
                       {"method", l.method},
                       {"source_size", l.sourceSize},
                       {"computed_size", l.computedSize},
                       {"samples", l.samples}});
  }
  const std::string mapping(mappingName(o.specular.mapping));
  addCube(plan, out, "specular", "specular", r.specular,
          {{"variant", "standard"},
           {"roughness", roughness},
           {"mapping", mapping},
           {"methods", methods}});
  if (r.specularF0Zero) {
    addCube(plan, out, "specular", "specular_f0_0", *r.specularF0Zero,
            {{"variant", "fresnel_f0_0"}, {"roughness", roughness}, {"mapping", mapping}});
    addCube(plan, out, "specular", "specular_f0_1", *r.specularF0One,
            {{"variant", "fresnel_f0_1"}, {"roughness", roughness}, {"mapping", mapping}});
  }
}

// The DFG table: 2D RGBA16F KTX2 (and float EXR).
void addDfg(OutputPlan& plan, const BakeResult& r, const BakeOptions& o,
            const BakeOutputOptions& out) {
  Ktx2Texture tex;
  tex.format = PixelFormat::Rgba16f;
  tex.levels = {{r.dfg}};
  plan.add("dfg.ktx2", [tex] { return encodeKtx2(tex); });
  plan.outputs.push_back({{"role", "dfg"},
                          {"path", "dfg.ktx2"},
                          {"format", "ktx2"},
                          {"pixel_format", "rgba16f"},
                          {"vk_format", vulkanFormatName(PixelFormat::Rgba16f)},
                          {"size", {r.dfg.width, r.dfg.height}},
                          {"faces", 1},
                          {"levels", 1},
                          {"channels", {"A", "B", "diffuse"}},
                          {"samples", o.dfgSamples}});
  if (out.exr) {
    plan.add("dfg.exr", [&r] { return encodeExr(r.dfg, ExrPixelType::Float); });
    plan.outputs.push_back({{"role", "dfg"},
                            {"path", "dfg.exr"},
                            {"format", "exr"},
                            {"size", {r.dfg.width, r.dfg.height}},
                            {"channels", {"A", "B", "diffuse"}}});
  }
}

// SH9: a small JSON file, and the coefficients in the manifest.
void addSh(OutputPlan& plan, const BakeResult& r, const BakeOptions& o) {
  Json coefficients = Json::array();
  for (const auto& c : r.sh) coefficients.push_back(vec3Json(c));
  Json sh = {{"generator", fmt::format("ibl {}", kVersion)},
             {"coefficients", coefficients},
             {"windowed", o.shWindow != ShWindow::Off},
             {"window", shWindowName(o.shWindow)},
             {"band_factors", r.shWindowFactors}};
  shortenFloats(sh);
  plan.addText("sh.json", sh.dump(2) + "\n");
  plan.outputs.push_back({{"role", "sh"},
                          {"path", "sh.json"},
                          {"format", "json"},
                          {"size", {9, 1}},
                          {"coefficients", coefficients},
                          {"windowed", o.shWindow != ShWindow::Off},
                          {"window", shWindowName(o.shWindow)}});
}

constexpr int kSourcePreviewFaceSize = 256;

// The PNG previews: the material grid shaded with the bake, the source cross, the DFG table.
void addPreviews(OutputPlan& plan, const BakeResult& r, const BakeOptions& o, int cell) {
  plan.add("preview.png", [&r, &o, cell] {
    const Image grid = renderMaterialGrid(r, o, kPreviewColumns, cell);
    return encodePng(toneMapAces(grid, autoExposure(grid) + 0.5f));
  });
  plan.outputs.push_back(
      {{"role", "preview"},
       {"path", "preview.png"},
       {"format", "png"},
       {"size", {kPreviewColumns * cell, 2 * cell}},
       {"shows",
        "spheres of roughness 0..1 (columns), metal (top) and dielectric (bottom), ACES"}});
  // A view, not data (source.ktx2 has every level): at most 256^2 per face, so that a 1024^2
  // bake does not spend a second compressing a 4096 x 3072 PNG.
  const int shownLevel = levelOfSize(r.source, kSourcePreviewFaceSize);
  const int shownSize = r.source.levels[shownLevel][0].width;
  plan.add("source.png", [&r, shownLevel] {
    const Image cross = crossFromCube(r.source, shownLevel, false);
    return encodePng(toneMapAces(cross, autoExposure(cross)));
  });
  plan.outputs.push_back({{"role", "preview"},
                          {"path", "source.png"},
                          {"format", "png"},
                          {"size", {4 * shownSize, 3 * shownSize}},
                          {"shows", "source cube, horizontal cross, ACES"}});
  plan.add("dfg.png", [&r] { return encodePng(r.dfg); });
  plan.outputs.push_back({{"role", "preview"},
                          {"path", "dfg.png"},
                          {"format", "png"},
                          {"size", {r.dfg.width, r.dfg.height}},
                          {"shows", "DFG table, sRGB-encoded"}});
}

// manifest.json: generator, device, source, conventions and the outputs.
Json manifestJson(const BakeResult& r, const BakeOptions& o, const BakeSource& src,
                  const Json& outputs) {
  Json manifest;
  manifest["generator"] = fmt::format("ibl {}", kVersion);
  manifest["device"] = r.device;
  // An absolute path: the manifest is read from anywhere, not from where the bake ran. A sky's
  // description is no path, nor is an image in memory (format "array", the Python module's):
  // they are recorded as they were given.
  const std::string path = src.path.empty() ? std::string("(bundled default: sunset.exr)")
                           : isSkySpec(src.path) || src.format == "array"
                               ? src.path
                               : fs::absolute(src.path).lexically_normal().string();
  manifest["source"] = {{"path", path},
                        {"format", src.format},
                        {"layout", src.layout},
                        {"size", {src.width, src.height}},
                        {"replaced_pixels",
                         {{"nan", src.replaced.nan},
                          {"infinite", src.replaced.infinite},
                          {"negative", src.replaced.negative}}}};
  if (src.clamp > 0.0f)
    manifest["source"]["clamp"] = {{"limit", src.clamp},
                                   {"values", src.clampLoss.clamped},
                                   {"brightest", src.clampLoss.brightest},
                                   {"lost_power", src.clampLoss.lostPower}};
  Json targets = Json::array();
  for (EngineTarget t : o.targets) targets.push_back(std::string(targetName(t)));
  manifest["targets"] = targets;
  manifest["conventions"] = conventionsJson(o, r);
  manifest["outputs"] = outputs;
  shortenFloats(manifest);
  return manifest;
}

// The files an earlier bake in `dir` wrote, as its manifest lists them (relative paths inside
// the directory only: a manifest cannot make us remove anything else). Empty without one.
std::set<fs::path> filesOfEarlierBake(const fs::path& dir) {
  std::set<fs::path> listed;
  std::error_code ec;
  if (!fs::is_regular_file(dir / "manifest.json", ec)) return listed;
  try {
    const Json manifest = readJsonFile(dir / "manifest.json");
    const auto add = [&](const Json& p) {
      if (!p.is_string()) return;
      const fs::path rel = fs::path(p.get<std::string>()).lexically_normal();
      if (rel.empty() || rel.is_absolute() || *rel.begin() == "..") return;
      listed.insert(rel);
    };
    for (const auto& o : manifest.at("outputs")) {
      add(o.value("path", Json()));
      if (o.contains("paths"))
        for (const auto& p : o["paths"]) add(p);
    }
  } catch (const std::exception&) {
    return {};  // not a manifest of ours: remove nothing
  }
  listed.insert("manifest.json");
  return listed;
}

}  // namespace

void checkBakeOutputDirectory(const fs::path& outDir, bool force) {
  const std::string name = outDir.string();
  std::error_code ec;
  const fs::file_status status = fs::status(outDir, ec);
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) fail(name, "exists and is not a directory");
    const bool empty = fs::directory_iterator(outDir, ec) == fs::directory_iterator();
    if (ec) fail(name, fmt::format("cannot be read: {}", ec.message()));
    if (!empty && !force)
      fail(name,
           "exists and is not empty; pass --force to replace the bake in it (files the earlier "
           "bake's manifest lists are replaced or removed, others are kept)");
    if (::access(outDir.c_str(), W_OK | X_OK) != 0)
      fail(name, fmt::format("cannot be written: {}", std::strerror(errno)));
    return;
  }
  // A new directory: created beside its nearest existing ancestor, which must be a writable
  // directory.
  fs::path parent = fs::absolute(outDir, ec).lexically_normal().parent_path();
  while (!parent.empty() && !fs::exists(parent, ec) && parent != parent.root_path())
    parent = parent.parent_path();
  if (!fs::is_directory(parent, ec))
    fail(name, fmt::format("cannot be created: {} is not a directory", parent.string()));
  if (::access(parent.c_str(), W_OK | X_OK) != 0)
    fail(name, fmt::format("cannot be created in {}: {}", parent.string(), std::strerror(errno)));
}

namespace {

// Encodes every file (in parallel), then writes them all or none. A new directory is staged
// beside its destination and renamed into place. An existing directory must be empty, or
// `force` be given: then the new files replace the old ones together, the files the earlier
// bake's manifest lists that this bake does not write are removed, and other files are left.
std::vector<fs::path> writeAll(std::vector<PendingFile>& pending, const fs::path& outDir,
                               bool force, const ProgressFn& progress) {
  const std::string stage = fmt::format("writing {} files", pending.size());
  if (progress) progress(stage, 0.0);
  ProgressCounter encoded(progress, stage, static_cast<std::int64_t>(pending.size()));
  parallelFor(std::size_t{0}, pending.size(), [&](std::size_t i) {
    pending[i].bytes = pending[i].encode();
    encoded.advance();
  });
  std::vector<EncodedFile> files;
  for (auto& f : pending) files.push_back({outDir / f.path, std::move(f.bytes)});
  std::error_code ec;
  removeStaleTemporaries(outDir);
  // The whole bake must fit on the disk before its first byte is written.
  std::uint64_t total = 0;
  for (const auto& f : files) total += f.bytes.size();
  if (const auto free = freeDiskBytes(outDir); free && total > *free)
    fail(outDir.string(), fmt::format("the bake's {} files take {} bytes; the disk has {} free",
                                      files.size(), total, *free));
  if (!fs::exists(outDir, ec)) {
    StagingDirectory staging(stagingDirectoryFor(outDir, ::getpid()));
    try {
      for (const auto& f : files)
        writeFileAtomic(staging.path() / f.path.lexically_relative(outDir), f.bytes);
    } catch (const Error& e) {
      fs::remove_all(staging.path(), ec);
      // Name the user's directory, not the staging one.
      std::string message = e.what();
      const std::string from = staging.path().string(), to = outDir.string();
      for (auto at = message.find(from); at != std::string::npos; at = message.find(from, at))
        message.replace(at, from.size(), to);
      throw Error(message);
    } catch (...) {
      fs::remove_all(staging.path(), ec);
      throw;
    }
    staging.moveTo(outDir);
  } else {
    checkBakeOutputDirectory(outDir, force);
    const std::set<fs::path> earlier = filesOfEarlierBake(outDir);
    writeFilesTogether(files);
    std::set<fs::path> written;
    for (const auto& f : pending) written.insert(f.path.lexically_normal());
    for (const auto& old : earlier)
      if (!written.count(old)) fs::remove(outDir / old, ec);
  }
  std::vector<fs::path> paths;
  for (const auto& f : files) paths.push_back(f.path);
  return paths;
}

// The sheen pair of the ibl set: sheen.ktx2 (Charlie-prefiltered) and sheen_dfg.ktx2.
void addSheen(OutputPlan& plan, const BakeResult& r, const BakeOptions& o,
              const BakeOutputOptions& out) {
  Json roughness = Json::array();
  for (int m = 0; m < r.sheen->levelCount(); ++m)
    roughness.push_back(std::max(roughnessForLevel(m, r.sheen->levelCount(), o.specular.mapping),
                                 kMinSheenRoughness));
  addCube(plan, out, "sheen", "sheen", *r.sheen,
          {{"lobe", "Charlie (Estevez & Kulla 2017): D(h) (n.l), n = v"},
           {"roughness", roughness},
           {"mapping", std::string(mappingName(o.specular.mapping))},
           {"minimum_roughness", kMinSheenRoughness}});
  Ktx2Texture tex;
  tex.format = PixelFormat::Rgba16f;
  tex.levels = {{*r.sheenDfg}};
  plan.add("sheen_dfg.ktx2", [tex] { return encodeKtx2(tex); });
  plan.outputs.push_back({{"role", "sheen_dfg"},
                          {"path", "sheen_dfg.ktx2"},
                          {"format", "ktx2"},
                          {"pixel_format", "rgba16f"},
                          {"vk_format", vulkanFormatName(PixelFormat::Rgba16f)},
                          {"size", {r.sheenDfg->width, r.sheenDfg->height}},
                          {"faces", 1},
                          {"levels", 1},
                          {"u", "n.v = (i + 0.5) / W"},
                          {"v", "r = (j + 0.5) / H, row 0 first"},
                          {"channels", {"E", "0", "0"}},
                          {"visibility", std::string(sheenVisibilityName(o.sheenVisibility))},
                          {"r", fmt::format("E = integral of D_charlie V_{} (n.l): sheen = "
                                            "sheenColor * prefiltered sheen * E; base layer "
                                            "scaled by 1 - max(sheenColor) * E",
                                            sheenVisibilityName(o.sheenVisibility))}});
}

}  // namespace

namespace {

// Every file of a bake, manifest.json last, planned but not encoded.
OutputPlan planBakeOutputs(const BakeResult& r, const BakeOptions& o, const BakeOutputOptions& out,
                           const BakeSource& src, const fs::path& outDir) {
  OutputPlan plan;
  if (o.wants(EngineTarget::Ibl)) {
    addSpecular(plan, r, o, out);
    addCube(plan, out, "irradiance", "irradiance", r.irradiance, {{"stores", "E / pi"}});
    addCube(plan, out, "source", "source", r.source, {});
    addDfg(plan, r, o, out);
    addSh(plan, r, o);
    if (r.sheen && r.sheenDfg) addSheen(plan, r, o, out);
    for (const auto& [role, cube] : out.extraCubes) addCube(plan, out, role, role, *cube, {});
    if (out.preview) addPreviews(plan, r, o, out.previewCell);
  }
  const bool panorama =
      src.layout == "equirect" || src.layout == "mirrorball" || src.layout == "angular";
  std::string name = outDir.filename().string();
  if (name.empty()) name = outDir.parent_path().filename().string();  // "dir/"
  addTargetOutputs(plan, r, o, out, name, panorama);
  Json manifest = manifestJson(r, o, src, plan.outputs);
  if (!out.manifestRecords.empty()) manifest.update(Json::parse(out.manifestRecords));
  plan.addText("manifest.json", manifest.dump(2) + "\n");
  return plan;
}

}  // namespace

std::vector<fs::path> writeBakeOutputs(const BakeResult& r, const BakeOptions& o,
                                       const BakeOutputOptions& out, const BakeSource& src,
                                       const fs::path& outDir) {
  OutputPlan plan = planBakeOutputs(r, o, out, src, outDir);
  return writeAll(plan.files, outDir, out.force, out.progress);
}

std::string bakeManifestJson(const BakeResult& r, const BakeOptions& o,
                             const BakeOutputOptions& out, const BakeSource& src,
                             const fs::path& outDir) {
  const std::vector<std::uint8_t> text =
      planBakeOutputs(r, o, out, src, outDir).files.back().encode();
  return std::string(text.begin(), text.end());
}

CubeMap readBakedCube(const fs::path& path) {
  const DecodedFile d = readImageFile(path);
  if (d.levels[0].size() != kFaceCount) fail(path.string(), "is not a cube map");
  CubeMap c;
  for (const auto& level : d.levels) {
    c.levels.emplace_back();
    for (int f = 0; f < kFaceCount; ++f) c.levels.back()[f] = level[f];
  }
  return c;
}

void scaleBake(BakeResult& r, double factor, std::string_view name) {
  std::vector<CubeMap*> cubes = {&r.source, &r.specular, &r.irradiance};
  for (std::optional<CubeMap>* c :
       {&r.specularF0Zero, &r.specularF0One, &r.sheen, &r.filamentSpecular, &r.babylonSpecular})
    if (c->has_value()) cubes.push_back(&**c);
  if (!(factor > 0.0) || !std::isfinite(factor))
    fail(name, fmt::format("cannot scale by {}: the factor must be positive and finite", factor));
  // Checked on every map before any is changed: all or nothing.
  float largest = 0.0f;
  for (const CubeMap* c : cubes)
    for (const auto& level : c->levels)
      for (const Image& face : level)
        for (const glm::vec3& p : face.pixels)
          largest =
              std::max(largest, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
  if (static_cast<double>(largest) * factor > std::numeric_limits<float>::max())
    fail(name, fmt::format("scaled by {:g}, its largest value {:g} would exceed the range of a "
                           "float (3.4e38)",
                           factor, largest));
  const float k = static_cast<float>(factor);
  for (CubeMap* c : cubes)
    for (auto& level : c->levels)
      for (Image& face : level)
        for (glm::vec3& p : face.pixels) p *= k;
  for (glm::vec3& coefficient : r.sh) coefficient *= k;
}

BakeResult loadBake(const fs::path& dir, BakeOptions* options) {
  const fs::path manifestPath = dir / "manifest.json";
  const Json manifest = readJsonFile(manifestPath);
  // The engine targets' files are the engines' to read: rendering reads the ibl set.
  if (manifest.contains("targets") && manifest["targets"].is_array()) {
    std::vector<std::string> targets;
    for (const auto& t : manifest["targets"])
      if (t.is_string()) targets.push_back(t.get<std::string>());
    if (std::find(targets.begin(), targets.end(), "ibl") == targets.end()) {
      std::string list;
      for (const auto& t : targets) list += (list.empty() ? "" : ",") + t;
      fail(dir.string(),
           fmt::format("holds the {} target's files only; rendering reads the ibl set: bake "
                       "again with --target ibl,{}",
                       list, list));
    }
  }
  BakeResult r;
  const auto cube = [&](const std::string& file) { return readBakedCube(dir / file); };
  // Every file the manifest lists must be there, and each KTX2 file hold what it says.
  const auto checkAgainstManifest = [&](const Json& o) {
    std::vector<std::string> paths;
    if (o.contains("paths"))
      for (const auto& p : o.at("paths")) paths.push_back(p.get<std::string>());
    else
      paths.push_back(o.at("path").get<std::string>());
    for (const auto& p : paths) {
      std::error_code ec;
      if (!fs::is_regular_file(dir / p, ec))
        fail((dir / p).string(), "is listed in manifest.json but missing");
    }
    if (o.at("format") != "ktx2") return;
    const DecodedFile d = readImageFile(dir / paths[0]);
    const int faces = o.value("faces", 1), levels = o.value("levels", 1);
    const int width = o.at("size").at(0).get<int>();
    if (static_cast<int>(d.levels.size()) != levels ||
        static_cast<int>(d.levels[0].size()) != faces || d.levels[0][0].width != width)
      fail((dir / paths[0]).string(),
           fmt::format("holds {} level(s) of {} face(s) of width {}; manifest.json says {} of {} "
                       "of width {}",
                       d.levels.size(), d.levels[0].size(), d.levels[0][0].width, levels, faces,
                       width));
  };
  try {
    for (const auto& o : manifest.at("outputs")) checkAgainstManifest(o);
    r.specular = cube("specular.ktx2");
    r.irradiance = cube("irradiance.ktx2");
    r.source = cube("source.ktx2");
    r.dfg = readImageFile(dir / "dfg.ktx2").levels.at(0).at(0);
    for (const auto& o : manifest.at("outputs")) {
      if (o.at("role") == "sheen" && o.at("path") == "sheen.ktx2") r.sheen = cube("sheen.ktx2");
      if (o.at("role") == "sheen_dfg" && o.at("path") == "sheen_dfg.ktx2") {
        r.sheenDfg = readImageFile(dir / "sheen_dfg.ktx2").levels.at(0).at(0);
        // Bakes from before the choice recorded none: their tables used Neubelt's.
        const std::string name = o.value("visibility", "neubelt");
        const std::optional<SheenVisibility> v = parseSheenVisibility(name);
        if (!v)
          fail(manifestPath.string(),
               fmt::format("sheen_dfg.ktx2: unknown visibility '{}' (charlie or neubelt)", name));
        if (options) options->sheenVisibility = *v;
      }
      if (o.at("role") == "sh")
        for (int k = 0; k < 9; ++k)
          for (int c = 0; c < 3; ++c) r.sh[k][c] = o.at("coefficients").at(k).at(c).get<float>();
      if (o.at("role") == "specular" && o.value("variant", "") == "standard" &&
          o.at("format") == "ktx2") {
        for (const auto& v : o.at("roughness"))
          r.specularLevels.push_back({v.get<float>(), "loaded", 0, 0});
        if (options)
          options->specular.mapping = o.at("mapping") == "frostbite" ? RoughnessMapping::Frostbite
                                                                     : RoughnessMapping::Linear;
      }
    }
  } catch (const nlohmann::json::exception& e) {
    fail(manifestPath.string(), fmt::format("unexpected content: {}", e.what()));
  }
  if (options) options->specular.size = r.specular.size();
  return r;
}

}  // namespace ibl
