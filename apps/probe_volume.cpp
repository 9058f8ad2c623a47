// `ibl probe SCENE --volume NX,NY,NZ --bounds BOX -o DIR`: an irradiance volume (Majercik et
// al. 2019) captured by the path tracer, probe by probe, after each probe's relocation out of
// the geometry; its shards (--shard K/N) and their merge (--merge DIR). The volume itself is
// the library's (ibl/render/irradiance_volume.hpp).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <unistd.h>

#include "ibl/core/error.hpp"
#include "ibl/render/irradiance_volume.hpp"
#include "preflight.hpp"
#include "probe.hpp"

namespace ibl::cli {

namespace {

namespace fs = std::filesystem;

// The options that set a volume's maps and lookup, for the checks.
constexpr const char* kVolumeOnly[] = {"--volume-size", "--volume-texels", "--normal-bias",
                                       "--view-bias"};

VolumeOptions volumeOptions(const ProbeCliOptions& o) {
  VolumeOptions v;
  v.captureSize = o.volumeSize;
  v.irradianceTexels = o.volumeTexels;
  v.distanceTexels = 2 * o.volumeTexels;
  if (o.normalBias >= 0.0f) v.normalBias = o.normalBias;
  if (o.viewBias >= 0.0f) v.viewBias = o.viewBias;
  return v;
}

// "probe_I_J_K at (x, y, z)", for messages.
std::string probeName(const VolumeGrid& g, int index) {
  const glm::vec3 x = volumeProbePosition(g, index);
  return fmt::format("probe_{}_{}_{} at ({:.3g}, {:.3g}, {:.3g})", index % g.counts.x,
                     index / g.counts.x % g.counts.y, index / (g.counts.x * g.counts.y), x.x, x.y,
                     x.z);
}

// The output directory can take the volume's files (`stem`): a directory that can be written or
// created, and, unless --force, none of the files there already.
void checkVolumeOutput(const ProbeCliOptions& o, const std::string& stem) {
  checkBakeOutputDirectory(o.output, true);
  if (o.force) return;
  for (const std::string& name : volumeFileNames(stem)) {
    const fs::path path = fs::path(o.output) / name;
    std::error_code ec;
    if (fs::exists(path, ec))
      fail(path.string(), "exists; pass --force to replace the volume's files");
  }
}

// Relocates the probes `which` (the paper's relocation: out of the geometry, away from walls),
// records each in the volume and warns about those it switched off. Returns the probes still
// on.
std::vector<int> relocate(const Scene& scene, IrradianceVolume& volume,
                          const std::vector<int>& which, const GlobalOptions& global) {
  const std::vector<ProbeRelocation> moved = relocateProbes(scene, volume.grid, which);
  std::vector<int> on;
  for (std::size_t i = 0; i < which.size(); ++i) {
    volume.probes[static_cast<std::size_t>(which[i])] = moved[i];
    if (moved[i].on)
      on.push_back(which[i]);
    else if (!global.quiet)
      fmt::print(stderr, "ibl: warning: probe {} switched off: {}\n",
                 probeName(volume.grid, which[i]), moved[i].reason);
  }
  return on;
}

// Whether two volumes (a merge's shards) are parts of one: the same grid, maps, lookup and
// capture settings.
bool sameVolume(const IrradianceVolume& a, const IrradianceVolume& b) {
  const VolumeOptions &x = a.options, &y = b.options;
  return a.grid.counts == b.grid.counts && a.boundsLo == b.boundsLo && a.boundsHi == b.boundsHi &&
         x.captureSize == y.captureSize && x.irradianceTexels == y.irradianceTexels &&
         x.distanceTexels == y.distanceTexels && x.distanceRays == y.distanceRays &&
         x.normalBias == y.normalBias && x.viewBias == y.viewBias &&
         captureRecordJson(a.capture, 0.0) == captureRecordJson(b.capture, 0.0);
}

}  // namespace

void addVolumeOptions(CLI::App* cmd, ProbeCliOptions& o) {
  const VolumeOptions defaults;
  cmd->add_option("--volume", o.volume,
                  "An irradiance volume of NX,NY,NZ probes at the cell centers of --bounds "
                  "(irradiance and distance atlases and volume.json)");
  cmd->add_option("--volume-size", o.volumeSize,
                  "Volume: the octahedral map path traced per probe, texels per side")
      ->check(numberIn(4, 256))
      ->capture_default_str();
  cmd->add_option("--volume-texels", o.volumeTexels,
                  "Volume: the irradiance tile's texels per side (the distance tile's: twice "
                  "as many)")
      ->check(numberIn(2, 32))
      ->capture_default_str();
  cmd->add_option("--normal-bias", o.normalBias,
                  fmt::format("Volume: the shaded point's offset along the normal, in units of "
                              "the smallest spacing (default {})",
                              defaults.normalBias))
      ->check(numberIn(0.0, 1.0));
  cmd->add_option("--view-bias", o.viewBias,
                  fmt::format("Volume: the shaded point's offset toward the viewer, in units of "
                              "the smallest spacing (default {})",
                              defaults.viewBias))
      ->check(numberIn(0.0, 1.0));
}

void checkVolumeOptions(const ProbeCliOptions& o) {
  if (o.volume.empty()) {
    for (const char* option : kVolumeOnly)
      if (given(o, option))
        failUsage(option, "sets the irradiance volume, which needs --volume NX,NY,NZ");
    return;
  }
  if (!o.at.empty() || !o.grid.empty())
    failUsage(o.at.empty() ? "--grid" : "--at",
              "contradicts --volume: give one probe (--at), a grid of probes (--grid) or an "
              "irradiance volume (--volume)");
  for (const char* option : {"--proxy", "--influence", "--fade", "--rotation"})
    if (given(o, option))
      failUsage(option, "shapes a local probe; a volume's probes (--volume) have none");
  if (given(o, "--size"))
    failUsage("--size",
              "is the cube face size of local probes; a volume's map is --volume-size (--volume)");
  parseProbeCounts(o.volume, "--volume");
  if (o.bounds.empty()) failUsage("--volume", "needs --bounds MINX,MINY,MINZ,MAXX,MAXY,MAXZ");
  parseBounds(o.bounds);
}

void runVolume(const ProbeCliOptions& o, const GlobalOptions& global) {
  const glm::ivec3 counts = parseProbeCounts(o.volume, "--volume");
  const auto [lo, hi] = parseBounds(o.bounds);
  checkSceneOptions(o.scene);
  CaptureOptions capture = o.capture;
  capture.size = o.volumeSize;  // the record's map size
  IrradianceVolume volume = makeVolume(lo, hi, counts, volumeOptions(o), capture);
  const int total = volumeProbeCount(volume.grid);
  // The probes this run captures, and the files it writes.
  std::vector<int> mine;
  std::string stem = "volume";
  const std::optional<Shard> shard =
      o.shard.empty() ? std::nullopt : std::optional<Shard>(parseShard(o.shard));
  for (int i = 0; i < total; ++i)
    if (!shard || shard->owns(static_cast<std::size_t>(i))) mine.push_back(i);
  if (shard) stem = fs::path(shardListName("volume", shard->k, shard->n)).stem().string();
  refuseInputsInside(o.output, sceneInputFiles(o.scene));
  checkVolumeOutput(o, stem);
  Scene scene = loadCaptureScene(o, global);
  const auto [sceneLo, sceneHi] = scene.bounds();
  for (int i = 0; i < total; ++i)
    requireInsideScene(volumeProbePosition(volume.grid, i), sceneLo, sceneHi, "--bounds");
  const LoadedBake env = loadOrBake(o.scene, global);
  scene.lights.insert(scene.lights.end(), env.lights.begin(), env.lights.end());
  const auto start = std::chrono::steady_clock::now();  // the volume's own time, the bake's not
  const std::vector<int> on = relocate(scene, volume, mine, global);
  const bool showProgress = !global.quiet && ::isatty(STDERR_FILENO);
  for (std::size_t i = 0; i < on.size(); ++i) {
    const double before = volume.captureMilliseconds;
    captureVolumeProbes(scene, volume, {on[i]}, env.bake, env.options, [&](float f) {
      if (showProgress) fmt::print(stderr, "\r  capturing {:3.0f} %", 100.0f * f);
    });
    if (showProgress) fmt::print(stderr, "\r");
    if (!global.quiet)
      fmt::print(stderr, "[{}/{}] probe {}: capture {:.2f} s\n", i + 1, on.size(),
                 probeName(volume.grid, on[i]), (volume.captureMilliseconds - before) / 1000.0);
  }
  writeVolume(volume, o.output, stem);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!global.quiet)
    fmt::print(
        stderr, "{} probes in {:.1f} s ({:.2f} s per probe){}; volume: {}\n", on.size(), seconds,
        on.empty() ? 0.0 : seconds / static_cast<double>(on.size()),
        on.size() == mine.size() ? "" : fmt::format(", {} switched off", mine.size() - on.size()),
        (fs::path(o.output) / (stem + ".json")).string());
}

void mergeVolumeShards(const fs::path& dir, const std::vector<fs::path>& parts,
                       const GlobalOptions& global) {
  for (const std::string& name : volumeFileNames()) requireWritableFile(dir / name);
  std::optional<IrradianceVolume> merged;
  std::set<int> seen;
  double milliseconds = 0.0;
  int shards = 0;
  for (const fs::path& part : parts) {
    if (part.extension() != ".json") continue;
    const IrradianceVolume v = loadVolume(dir, part.stem().string());
    if (!merged)
      merged = makeVolume(v.boundsLo, v.boundsHi, v.grid.counts, v.options, v.capture);
    else if (!sameVolume(*merged, v))
      fail(part.string(),
           "belongs to another volume (its counts, bounds, maps, biases or capture settings "
           "differ)");
    // A shard's own probes: those it captured, and those its relocation switched off.
    for (std::size_t i = 0; i < v.probes.size(); ++i)
      if ((v.captured[i] || !v.probes[i].on) && seen.insert(static_cast<int>(i)).second)
        copyVolumeProbe(v, *merged, static_cast<int>(i));
    milliseconds += v.captureMilliseconds;
    ++shards;
  }
  if (!merged) fail(dir.string(), "holds no volume.shard-K-of-N.json to merge");
  const int total = volumeProbeCount(merged->grid);
  if (static_cast<int>(seen.size()) != total)
    fail(dir.string(), missingProbesMessage(merged->grid.counts, seen, parts, "volume"));
  merged->captureMilliseconds = milliseconds;
  writeVolume(*merged, dir);
  if (!global.quiet)
    fmt::print(stderr, "merged {} volume shards into {}: {} probes\n", shards,
               (dir / "volume.json").string(), total);
}

}  // namespace ibl::cli
