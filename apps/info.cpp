// `ibl info`: what is in an image file, and what it means as an environment.
#include <cstdio>
#include <string>

#include <fmt/core.h>
#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "ibl/core/error.hpp"
#include "ibl/core/stats.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"

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

void runInfo(const InfoOptions& o) {
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
  if (env) sanitizeEnvironment(*env);

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
  glm::dvec3 integral(0.0);
  std::optional<glm::vec3> brightest;
  if (env) {
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
  }
}

}  // namespace

void addInfoCommand(CLI::App& app, const GlobalOptions&) {
  auto opts = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand("info",
                                     "Describe an image file: format, layout, size, "
                                     "value range, invalid pixels, radiant integral");
  cmd->add_option("file", opts->file,
                  "Image file (.hdr, .exr, .png, .jpg, .ktx2); a path with {face} names six face "
                  "files")
      ->required();
  cmd->add_option("--input-layout", opts->inputLayout, "Layout (default: from the shape)")
      ->check(CLI::IsMember({"equirect", "cross", "hcross", "vcross", "hstrip", "vstrip", "faces",
                             "mirrorball", "angular"}));
  cmd->add_option("--layer", opts->layer, "EXR layer to describe (default: as `ibl convert`)");
  cmd->add_flag("--json", opts->json, "Print JSON instead of text");
  cmd->callback([opts] { runInfo(*opts); });
}

}  // namespace ibl::cli
