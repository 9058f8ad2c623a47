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
  bool json = false;
};

void runInfo(const InfoOptions& o) {
  DecodedFile d = readImageFile(o.file);
  const Image& base = d.levels[0][0];
  const int faces = static_cast<int>(d.levels[0].size());
  const int levels = static_cast<int>(d.levels.size());
  const std::string format(fileFormatName(d.format));
  const int channels = d.channels;
  const std::string detail = d.detail;

  // Statistics of the stored values, before anything is replaced.
  ImageStats stats = imageStats(base);
  for (int f = 1; f < faces; ++f) {
    const ImageStats s = imageStats(d.levels[0][f]);
    stats.min = glm::min(stats.min, s.min);
    stats.max = glm::max(stats.max, s.max);
    stats.mean += s.mean;
    stats.invalid += s.invalid;
  }
  stats.mean /= static_cast<double>(faces);

  std::optional<Environment> env;
  std::optional<Layout> layout;
  if (!o.inputLayout.empty()) layout = parseLayout(o.inputLayout);
  if (faces == kFaceCount || layout || layoutFromShape(base.width, base.height)) {
    env = environmentFromFile(std::move(d), {layout}, o.file);
    sanitizeEnvironment(*env);
  }

  nlohmann::ordered_json j;
  j["file"] = o.file;
  j["format"] = format;
  j["detail"] = detail;
  j["channels"] = channels;
  j["width"] = base.width;
  j["height"] = base.height;
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
  fmt::print("layout      {}\n", env ? layoutName(env->layout) : "2d image (not an environment)");
  fmt::print("size        {}x{}{}, {} level{}\n", base.width, base.height,
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
  cmd->add_option("file", opts->file, "Image file (.hdr, .exr, .png, .jpg, .ktx2)")->required();
  cmd->add_option("--input-layout", opts->inputLayout, "Layout (default: from the shape)")
      ->check(CLI::IsMember({"equirect", "cross", "hcross", "vcross"}));
  cmd->add_flag("--json", opts->json, "Print JSON instead of text");
  cmd->callback([opts] { runInfo(*opts); });
}

}  // namespace ibl::cli
