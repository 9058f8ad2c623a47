// `ibl sky`: a physically based clear sky as an HDR panorama or cube map, and its sun as a
// lights file.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "commands.hpp"
#include "ibl/core/error.hpp"
#include "ibl/env/export.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/render/light.hpp"
#include "preflight.hpp"
#include "sky.hpp"

namespace ibl::cli {

namespace {

SkyParameters skyParameters(const SkyCliOptions& o) {
  SkyParameters p;
  p.altitude = o.altitude;
  p.turbidity = o.turbidity;
  p.ozone = o.ozone;
  p.groundAlbedo = o.groundAlbedo;
  p.multipleScattering = !o.singleScattering;
  const bool angles = o.elevation || o.azimuth;
  const bool clock = !o.date.empty() || !o.time.empty();
  if (angles && clock)
    failUsage("--date",
              "contradicts --sun-elevation/--sun-azimuth: give the sun's angles or a date "
              "and time");
  if (!clock && (o.utcOffset || o.latitude || o.longitude))
    failUsage("--latitude",
              "--latitude, --longitude and --utc-offset place --date and --time: give "
              "those too");
  if (o.elevation) p.sunElevation = *o.elevation;
  if (o.azimuth) p.sunAzimuth = *o.azimuth;
  if (clock) {
    if (o.date.empty() || o.time.empty() || !o.latitude || !o.longitude)
      failUsage("--date", "a date and time need --date, --time, --latitude and --longitude");
    DateTime when;
    parseDate(o.date, when, "--date");
    parseClockTime(o.time, when, "--time");
    when.utcOffset = o.utcOffset.value_or(0.0);
    const SolarPosition sun = solarPosition(when, *o.latitude, *o.longitude, o.altitude);
    p.sunElevation = static_cast<float>(sun.elevation);
    p.sunAzimuth = static_cast<float>(sun.azimuth);
  }
  checkSkyParameters(p, "ibl sky");
  return p;
}

ExportOptions skyExportOptions(const SkyCliOptions& o, const GlobalOptions& global) {
  ExportOptions e;
  e.output = o.output;
  e.exrType = ExrPixelType::Float;  // cd/m^2 of the sun's disk exceed half floats
  e.ktx2Format = o.sunDisk ? PixelFormat::Rgba32f : PixelFormat::Rgba16f;
  e.warn = [&global](const std::string& message) {
    if (!global.quiet) fmt::print(stderr, "ibl: warning: {}\n", message);
  };
  return e;
}

void runSky(const SkyCliOptions& o, const GlobalOptions& global) {
  // (An empty --output is Python's panorama kept in memory, not the command's.)
  if (o.output.empty()) failUsage("--output", "is empty: name the file to write");
  const auto start = std::chrono::steady_clock::now();
  const SkyRequest request = checkSkyRequest(o, global);
  std::string deviceName;
  const std::vector<EncodedFile> files =
      writeSkyOutputs(o, request, computeSky(o, request, &deviceName), global);
  if (global.quiet) return;
  const SkyParameters& p = request.parameters;
  const Light sun = skySun(p);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print(stderr,
             "sky: sun at elevation {:.2f}, azimuth {:.2f} degrees: {:.0f} lx direct, color "
             "{:.3f},{:.3f},{:.3f}{}\n",
             p.sunElevation, p.sunAzimuth, sun.intensity, sun.color.x, sun.color.y, sun.color.z,
             o.sunDisk ? " (painted into the image)" : "");
  for (const auto& f : files)
    fmt::print(stderr, "wrote {} ({} bytes)\n", f.path.string(), f.bytes.size());
  fmt::print(stderr, "{}x{} in {:.2f} s on {}\n", request.width, request.height, seconds,
             deviceName);
}

}  // namespace

SkyRequest checkSkyRequest(const SkyCliOptions& o, const GlobalOptions& global) {
  SkyRequest r;
  r.parameters = skyParameters(o);
  int& width = r.width;
  int& height = r.height;
  if (std::sscanf(o.size.c_str(), "%dx%d", &width, &height) != 2 || width < 8 || height < 4 ||
      width > 16384 || height > 8192 || fmt::format("{}x{}", width, height) != o.size)
    failUsage("--size", fmt::format("\"{}\" is not WxH from 8x4 to 16384x8192", o.size));
  if (o.sunDisk && !o.sunJson.empty())
    failUsage("--sun-json",
              "contradicts --sun-disk: the sun is painted into the image or written as a "
              "light, not both");
  if (o.output.empty() && !o.sunJson.empty())
    failUsage("--sun-json", "is written beside the image: give an output file too");
  if (!o.output.empty()) {  // none: a panorama kept in memory (Python)
    const ExportOptions e = skyExportOptions(o, global);
    checkExportOptions(e);
    if (!o.sunJson.empty())
      for (const auto& path : possibleExportPaths(e))
        if (std::filesystem::weakly_canonical(std::filesystem::absolute(path)) ==
            std::filesystem::weakly_canonical(std::filesystem::absolute(o.sunJson)))
          failUsage("--sun-json", fmt::format("is the image's own file {}", path.string()));
    for (const auto& path : possibleExportPaths(e)) requireWritableFile(path);
    if (!o.sunJson.empty()) requireWritableFile(o.sunJson);
  }
  // Measured: the panorama, its encoding and the sky's tables, about 30 bytes per pixel.
  requireMemory(static_cast<std::uint64_t>(60e6 + 40.0 * width * height),
                fmt::format("--size {}", o.size), "compute a smaller sky");
  return r;
}

Image computeSky(const SkyCliOptions& o, const SkyRequest& request, std::string* deviceName) {
  const std::unique_ptr<gpu::Context> device = gpu::openComputeDevice(deviceChoice(o.device));
  if (deviceName) *deviceName = device ? device->device().name : std::string("the CPU");
  return gpu::skyPanoramaOn(device.get(), request.parameters, request.width, request.height,
                            o.sunDisk);
}

std::vector<EncodedFile> writeSkyOutputs(const SkyCliOptions& o, const SkyRequest& request,
                                         Image panorama, const GlobalOptions& global) {
  Environment env;
  env.layout = Layout::Equirect;
  env.equirect = std::move(panorama);
  std::vector<EncodedFile> files = encodeEnvironment(env, skyExportOptions(o, global));
  const Light sun = skySun(request.parameters);
  if (!o.sunJson.empty()) {
    const std::string text = sun.intensity > 0.0f
                                 ? fmt::format("{{\"lights\": [{}]}}\n", lightJson(sun))
                                 : std::string("{\"lights\": []}\n");
    files.push_back({o.sunJson, std::vector<std::uint8_t>(text.begin(), text.end())});
  }
  writeFilesTogether(files);
  return files;
}

void addSkyCommand(CLI::App& app, const GlobalOptions& global) {
  auto opts = std::make_shared<SkyCliOptions>();
  CLI::App* cmd = addSkyOptions(app, *opts);
  cmd->callback([opts, &global] { runSky(*opts, global); });
}

CLI::App* addSkyOptions(CLI::App& app, SkyCliOptions& o) {
  SkyCliOptions* opts = &o;
  CLI::App* cmd = app.add_subcommand(
      "sky",
      "A physically based clear sky (Rayleigh, Mie, ozone, multiple scattering; spectral) as "
      "linear Rec.709 radiance in cd/m^2, and its sun as a light in lux");
  cmd->add_option("-o,--output", opts->output,
                  "Output file: .exr (equirect, 32-bit float), .hdr, or .ktx2 (cube map); missing "
                  "folders are created")
      ->required();
  cmd->add_option("--sun-elevation", opts->elevation,
                  "The sun's elevation above the horizon, degrees (default 30)")
      ->check(numberIn(-90.0f, 90.0f));
  cmd->add_option("--sun-azimuth", opts->azimuth,
                  "The sun's compass azimuth, degrees from north (-Z) toward east (+X) (default "
                  "180: south)")
      ->check(numberIn(-360.0f, 360.0f));
  cmd->add_option("--date", opts->date, "Date YYYY-MM-DD (with --time, --latitude, --longitude)");
  cmd->add_option("--time", opts->time, "Local clock time HH:MM[:SS]");
  cmd->add_option("--utc-offset", opts->utcOffset,
                  "Hours east of UTC of the local time (default 0)")
      ->check(numberIn(-14.0, 14.0));
  cmd->add_option("--latitude", opts->latitude, "Degrees, north positive")
      ->check(numberIn(-90.0, 90.0));
  cmd->add_option("--longitude", opts->longitude, "Degrees, east positive")
      ->check(numberIn(-180.0, 180.0));
  cmd->add_option("--altitude", opts->altitude, "The observer's altitude above the ground, meters")
      ->check(numberIn(0.0f, 80000.0f))
      ->capture_default_str();
  cmd->add_option("--turbidity", opts->turbidity,
                  "1 + aerosol optical depth / molecular optical depth at 550 nm (1: pure air, "
                  "2: clear, 4+: hazy)")
      ->check(numberIn(1.0f, 20.0f))
      ->capture_default_str();
  cmd->add_option("--ozone", opts->ozone, "Ozone column, Dobson units")
      ->check(numberIn(0.0f, 1000.0f))
      ->capture_default_str();
  cmd->add_option("--ground-albedo", opts->groundAlbedo, "Albedo of the (Lambertian) ground")
      ->check(numberIn(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--size", opts->size, "Panorama size WxH")->capture_default_str();
  cmd->add_option(
      "--sun-json", opts->sunJson,
      "Also write the sun as a lights file ({\"lights\": [{\"type\": \"sun\", ...}]}: "
      "direction, lux after the atmosphere, color, angular diameter) for --lights; missing folders "
      "are created");
  cmd->add_flag("--sun-disk", opts->sunDisk,
                "Paint the sun's limb-darkened disk into the image instead (carrying its full "
                "illuminance)");
  cmd->add_option("--device", opts->device,
                  "cpu, gpu (the sky's tables and panorama in Vulkan compute), or auto (a real "
                  "GPU if present)")
      ->check(CLI::IsMember({"cpu", "gpu", "auto"}))
      ->capture_default_str();
  cmd->add_flag("--single-scattering", opts->singleScattering,
                "Leave out multiple scattering (for comparison)");
  return cmd;
}

}  // namespace ibl::cli
