#pragma once
// `ibl sky`'s options and steps, for the command and the Python module (python/): both parse
// the same options and run the same code.
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/io/file_io.hpp"

namespace ibl::cli {

struct SkyCliOptions {
  std::string output;
  std::optional<float> elevation, azimuth;
  std::string date, time;
  std::optional<double> utcOffset, latitude, longitude;
  float altitude = 0.0f;
  float turbidity = 2.0f;
  float ozone = 300.0f;
  float groundAlbedo = 0.3f;
  std::string size = "2048x1024";
  std::string sunJson;
  bool sunDisk = false;
  bool singleScattering = false;
  std::string device = "cpu";
};

// Adds the subcommand "sky" to `app` with its options, stored into `o` (no callback).
CLI::App* addSkyOptions(CLI::App& app, SkyCliOptions& o);

// The sky the options ask for, after every check that needs no work (the outputs' only when
// o.output is given).
struct SkyRequest {
  SkyParameters parameters;
  int width = 0, height = 0;
};
SkyRequest checkSkyRequest(const SkyCliOptions& o, const GlobalOptions& global);
// The panorama (linear Rec.709, cd/m^2), on --device (its name into `deviceName`).
Image computeSky(const SkyCliOptions& o, const SkyRequest& request,
                 std::string* deviceName = nullptr);
// Encodes and writes o.output (and --sun-json) as `ibl sky` does, the panorama moved into the
// encoder; returns the files written.
std::vector<EncodedFile> writeSkyOutputs(const SkyCliOptions& o, const SkyRequest& request,
                                         Image panorama, const GlobalOptions& global);

}  // namespace ibl::cli
