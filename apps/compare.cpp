// `ibl compare`: how far an image is from a reference.
#include <cstdio>
#include <filesystem>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "compare.hpp"
#include "ibl/core/error.hpp"
#include "ibl/core/stats.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"
#include "preflight.hpp"

namespace ibl::cli {

namespace {

struct FlatImage {
  Image image;
  FileFormat format;
};

FlatImage readFlat(const std::string& path) {
  DecodedFile d = readImageFile(path);
  if (d.levels[0].size() != 1) fail(path, "is a cube map; compare flat images");
  return {std::move(d.levels[0][0]), d.format};
}

// PNG and JPEG hold display-referred (exposed, tone-mapped) values; the other formats hold
// linear radiance. Comparing one with the other measures the tone curve, not the renderer.
bool displayReferred(FileFormat format) {
  return format == FileFormat::Png || format == FileFormat::Jpg;
}

nlohmann::ordered_json errorsJson(const ChannelErrors& e) {
  return {{"rmse", e.rmse},
          {"relative_mse", e.relativeMse},
          {"mean_relative_error", e.meanRelativeError},
          {"max_error", e.maxError},
          {"psnr_db", e.psnr}};
}

void requireSameSize(const Image& a, const Image& b, const std::string& nameA,
                     const std::string& nameB) {
  if (a.width != b.width || a.height != b.height)
    fail(nameA,
         fmt::format("is {}x{} but {} is {}x{}", a.width, a.height, nameB, b.width, b.height));
}

int runCompare(const CompareOptions& o) {
  const ImageComparison c = compareFiles(o);
  if (o.json) {
    fmt::print("{}\n", comparisonJson(c).dump(2));
  } else {
    fmt::print("compared {} pixels of {} against {}\n", c.pixels, o.a, o.b);
    fmt::print("{:8} {:>12} {:>12} {:>12} {:>12} {:>9}\n", "channel", "RMSE", "rel. MSE",
               "mean rel.", "max", "PSNR dB");
    const char* names[4] = {"R", "G", "B", "overall"};
    for (int k = 0; k < 4; ++k) {
      const ChannelErrors& e = k < 3 ? c.channel[k] : c.overall;
      fmt::print("{:8} {:12.6g} {:12.6g} {:12.6g} {:12.6g} {:9.2f}\n", names[k], e.rmse,
                 e.relativeMse, e.meanRelativeError, e.maxError, e.psnr);
    }
    fmt::print("luminance: frame error {:.4g}, median 4x4 block error {:.4g}, off by 2x {:.4g} %\n",
               c.frame.frameError, c.frame.medianBlockError, 100.0 * c.frame.offBy2x);
  }
  if (o.maxRelError >= 0.0 && c.overall.meanRelativeError > o.maxRelError) {
    fmt::print(stderr, "ibl: mean relative error {:.6g} exceeds --max-rel-error {:.6g}\n",
               c.overall.meanRelativeError, o.maxRelError);
    return 3;
  }
  return 0;
}

}  // namespace

ImageComparison compareFiles(const CompareOptions& o) {
  std::vector<std::filesystem::path> inputs;
  for (const std::string& input : {o.a, o.b, o.mask})
    if (!input.empty()) {
      requireReadable(input);
      inputs.emplace_back(input);
    }
  if (!o.errorPng.empty()) {
    refuseOverwritingInputs({o.errorPng}, inputs);
    requireWritableFile(o.errorPng);
  }
  const FlatImage fa = readFlat(o.a), fb = readFlat(o.b);
  if (displayReferred(fa.format) != displayReferred(fb.format)) {
    const bool aDisplay = displayReferred(fa.format);
    fail(o.a,
         fmt::format("is {} but {} is {}: compare two linear images (EXR, HDR) or two "
                     "display images (PNG, JPEG)",
                     aDisplay ? "a display image (tone-mapped PNG/JPEG)" : "linear radiance", o.b,
                     aDisplay ? "linear radiance" : "a display image (tone-mapped PNG/JPEG)"));
  }
  requireSameSize(fa.image, fb.image, o.a, o.b);
  std::vector<float> mask;
  if (!o.mask.empty()) {
    const Image m = readFlat(o.mask).image;
    if (m.width != fa.image.width || m.height != fa.image.height)
      fail(o.mask, "mask size differs from the images");
    for (const auto& p : m.pixels) mask.push_back(p.x);
  }
  return compareLoaded(o, fa.image, fb.image, mask, o.a, o.b, o.mask);
}

Image readFlatImage(const std::string& path) {
  return readFlat(path).image;
}

ImageComparison compareLoaded(const CompareOptions& o, const Image& a, const Image& b,
                              const std::vector<float>& mask, const std::string& nameA,
                              const std::string& nameB, const std::string& maskName) {
  requireSameSize(a, b, nameA, nameB);
  if (!mask.empty() && mask.size() != a.pixels.size())
    fail(maskName, "mask size differs from the images");
  const ImageComparison c = compareImages(a, b, mask.empty() ? nullptr : &mask);
  if (!o.errorPng.empty())
    writeFileAtomic(o.errorPng, encodePng(errorFalseColor(a, b, o.errorScale)));
  return c;
}

nlohmann::ordered_json comparisonJson(const ImageComparison& c) {
  nlohmann::ordered_json j;
  j["pixels"] = c.pixels;
  j["overall"] = errorsJson(c.overall);
  j["r"] = errorsJson(c.channel[0]);
  j["g"] = errorsJson(c.channel[1]);
  j["b"] = errorsJson(c.channel[2]);
  j["frame"] = {{"frame_error", c.frame.frameError},
                {"median_block_error", c.frame.medianBlockError},
                {"off_by_2x", c.frame.offBy2x},
                {"blocks", c.frame.blocks},
                {"black_blocks", c.frame.blackBlocks}};
  return j;
}

void addCompareCommand(CLI::App& app, const GlobalOptions&) {
  auto opts = std::make_shared<CompareOptions>();
  CLI::App* cmd = addCompareOptions(app, *opts);
  cmd->callback([opts] {
    const int status = runCompare(*opts);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

CLI::App* addCompareOptions(CLI::App& app, CompareOptions& o) {
  CompareOptions* opts = &o;
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Error of an image against a reference (RMSE, relative MSE, PSNR; the luminance's frame "
      "error, median 4x4 block error and share of pixels off by 2x)");
  cmd->add_option("image", opts->a, "Image to judge")->required();
  cmd->add_option("reference", opts->b, "Reference image")->required();
  cmd->add_option("--mask", opts->mask, "Compare only where this image's red channel is > 0.5");
  cmd->add_option(
      "--error-png", opts->errorPng,
      "Write a false-color map of the relative error (PNG; missing folders are created)");
  cmd->add_option("--error-scale", opts->errorScale, "Relative error shown as red in --error-png")
      ->check(positiveNumber())
      ->capture_default_str();
  cmd->add_option("--max-rel-error", opts->maxRelError,
                  "Exit with status 3 if the mean relative error is above")
      ->check(nonNegativeNumber());
  cmd->add_flag("--json", opts->json, "Print JSON");
  return cmd;
}

}  // namespace ibl::cli
