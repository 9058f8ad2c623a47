#pragma once
// `ibl render`'s options and its image before it is written, for the command and the Python
// module (python/): both parse the same options and run the same code.
#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "ibl/render/renderer.hpp"
#include "scene_options.hpp"

namespace ibl::cli {

struct RenderCliOptions {
  SceneCliOptions scene;
  std::string output;
  std::string mode = "split-sum";
  float noise = 0.0f;
  int bounces = 4;
  bool exrExposed = false;
  unsigned seed = 1;
  std::string device = "cpu";
};

// Adds the subcommand "render" to `app` with its options, stored into `o` (no callback).
CLI::App* addRenderOptions(CLI::App& app, RenderCliOptions& o);

// A rendered image before it is written: linear radiance (with the bloom of --bloom) and
// coverage, and the exposure chosen for it.
struct RenderedImage {
  RenderResult result;
  float ev100 =
      0.0f;  // chosen (--ev100, the camera's settings or automatic), before --compensation
};
// Checks the options (and o.output unless it is empty), loads the scene and the bake, and
// renders; `progress` hears of the fraction done.
RenderedImage renderImage(const RenderCliOptions& o, const GlobalOptions& global,
                          const std::function<void(float)>& progress);
// Writes the image to o.output as `ibl render` does.
void writeRenderOutput(const RenderCliOptions& o, const RenderedImage& image);

}  // namespace ibl::cli
