// `ibl probe`: local light probes captured inside a scene by the path tracer and baked like an
// environment; one probe (--at), a grid (--grid, --bounds), a shard of a grid (--shard K/N),
// and merging the shards' lists (--merge). The irradiance volume (--volume): probe_volume.cpp.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/json_file.hpp"
#include "ibl/render/probe.hpp"
#include "preflight.hpp"
#include "probe.hpp"
#include "scene_options.hpp"

namespace ibl::cli {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// --proxy / --influence: a sphere or a box; `center` places `sphere:R`.
ProbeVolume parseVolume(const std::string& text, glm::vec3 center, glm::vec3 rotation,
                        const char* option) {
  const auto colon = text.find(':');
  const std::string shape = text.substr(0, colon);
  const std::string args = colon == std::string::npos ? "" : text.substr(colon + 1);
  if (shape == "sphere") {
    const std::size_t commas = static_cast<std::size_t>(std::count(args.begin(), args.end(), ','));
    const std::vector<float> v = parseNumbers(args, commas == 3 ? 4 : 1, option);
    const float radius = v.back();
    if (!(radius > 0.0f))
      failUsage(option, fmt::format("'{}': an empty sphere (radius <= 0)", text));
    return sphereVolume(commas == 3 ? glm::vec3(v[0], v[1], v[2]) : center, radius);
  }
  if (shape == "box") {
    const std::vector<float> v = parseNumbers(args, 6, option);
    const glm::vec3 lo(v[0], v[1], v[2]), hi(v[3], v[4], v[5]);
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
      failUsage(option,
                fmt::format("'{}': an empty box (min must be below max on every axis)", text));
    return boxVolume(lo, hi, rotation);
  }
  failUsage(option,
            fmt::format("'{}': expected sphere:R, sphere:X,Y,Z,R or box:MINX,MINY,MINZ,MAXX,"
                        "MAXY,MAXZ",
                        text));
}

float smallestHalfSize(const ProbeVolume& v) {
  return v.shape == 0 ? v.halfExtent.x
                      : std::min(v.halfExtent.x, std::min(v.halfExtent.y, v.halfExtent.z));
}

// One probe to capture: where it goes and what it is.
struct PlannedProbe {
  ProbePlacement placement;
  std::string directory;  // relative to OUTDIR ("" for a single probe: OUTDIR itself)
  glm::ivec3 index{0};
  int linear = 0;
};

// Captures, bakes and writes one probe (all its files or none). Returns the capture's time, or
// the reason the capture is unusable (nothing written then).
struct CaptureOutcome {
  double milliseconds = 0.0;
  std::string unusable;
};
CaptureOutcome captureAndBake(const ProbeCliOptions& o, const Scene& scene, const LoadedBake& env,
                              const PlannedProbe& p, const fs::path& dir, bool showProgress) {
  const ProbeCapture capture =
      captureProbe(scene, p.placement.position, env.bake, env.options, o.capture, [&](float f) {
        if (showProgress) fmt::print(stderr, "\r  capturing {:3.0f} %", 100.0f * f);
      });
  if (showProgress) fmt::print(stderr, "\r");
  const std::string unusable = unusableCaptureReason(CaptureSite{}, &capture);
  if (!unusable.empty()) return {capture.milliseconds, unusable};
  BakeOptions options;
  options.specular.size = o.capture.size;
  const LocalProbe probe = bakeProbe(capture, p.placement, o.capture, options);
  BakeOutputOptions output;
  output.force = o.force;
  output.preview = false;
  output.extraCubes = {{"coverage_specular", &probe.coverageSpecular},
                       {"coverage_irradiance", &probe.coverageIrradiance}};
  output.manifestRecords = fmt::format(
      "{{\"probe\": {}{}}}", probeRecordJson(p.placement, o.capture, capture.milliseconds),
      env.envScale.option.empty() ? "" : ", \"environment_scale\": " + env.envScale.recordJson());
  BakeSource source;
  source.path = "";
  source.format = "capture";
  source.layout = "cube";
  source.width = source.height = o.capture.size;
  writeBakeOutputs(probe.bake, options, output, source, dir);
  return {capture.milliseconds, {}};
}

// The grid's probes: cell centers of --grid over --bounds, each influencing its cell grown by
// the fade on every side, all with one proxy.
std::vector<PlannedProbe> planGrid(const ProbeCliOptions& o, const ProbeVolume* proxy,
                                   glm::vec3 rotation) {
  const glm::ivec3 counts = parseProbeCounts(o.grid, "--grid");
  if (o.bounds.empty()) failUsage("--grid", "needs --bounds MINX,MINY,MINZ,MAXX,MAXY,MAXZ");
  const auto [lo, hi] = parseBounds(o.bounds);
  const glm::vec3 cell = (hi - lo) / glm::vec3(counts);
  const float fade = o.fade >= 0.0f ? o.fade : 0.25f * std::min(cell.x, std::min(cell.y, cell.z));
  std::vector<PlannedProbe> probes;
  for (int k = 0; k < counts.z; ++k)
    for (int j = 0; j < counts.y; ++j)
      for (int i = 0; i < counts.x; ++i) {
        PlannedProbe p;
        p.index = {i, j, k};
        p.linear = static_cast<int>(probes.size());
        p.directory = fmt::format("probe_{}_{}_{}", i, j, k);
        const glm::vec3 cellLo = lo + cell * glm::vec3(p.index);
        p.placement.position = cellLo + 0.5f * cell;
        p.placement.hasProxy = proxy != nullptr;
        if (proxy) p.placement.proxy = *proxy;
        p.placement.influence = boxVolume(cellLo - fade, cellLo + cell + fade);
        p.placement.fade = fade;
        p.placement.rotationDegrees = rotation;
        probes.push_back(p);
      }
  return probes;
}

// The grid's list; `skipped` holds, by linear index, why a probe was left out (renders then
// never read it: loadProbes skips it).
Json gridListJson(const ProbeCliOptions& o, const std::vector<PlannedProbe>& probes,
                  const std::map<int, std::string>& skipped) {
  Json list = Json::array();
  for (const PlannedProbe& p : probes) {
    Json entry = {
        {"path", p.directory},
        {"index", {p.index.x, p.index.y, p.index.z}},
        {"linear", p.linear},
        {"position", {p.placement.position.x, p.placement.position.y, p.placement.position.z}}};
    if (const auto it = skipped.find(p.linear); it != skipped.end()) entry["skipped"] = it->second;
    list.push_back(entry);
  }
  return {{"grid", parseNumbers(o.grid, 3, "--grid")},
          {"bounds", parseNumbers(o.bounds, 6, "--bounds")},
          {"probes", list}};
}

// The files of `dir` named STEM.shard-*, sorted.
std::vector<fs::path> shardFiles(const std::string& dir, const std::string& stem) {
  std::vector<fs::path> parts;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().filename().string().starts_with(stem + ".shard-")) parts.push_back(e.path());
  std::sort(parts.begin(), parts.end());
  return parts;
}

// The grid's shard lists `parts` into probes.json, once every probe of the grid is there.
void mergeGridShards(const std::string& dir, const std::vector<fs::path>& parts,
                     const GlobalOptions& global) {
  requireWritableFile(fs::path(dir) / "probes.json");
  Json merged;
  std::set<int> seen;
  int total = -1;
  for (const fs::path& part : parts) {
    // Read in order (readJsonFile's map sorts the keys): probes.json is then the same bytes as
    // the one a grid captured in one process writes.
    const std::vector<std::uint8_t> bytes = readFileBytes(part);
    Json j = parseJsonText<Json>(
        std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), part.string());
    try {
      const int count =
          j.at("grid")[0].get<int>() * j.at("grid")[1].get<int>() * j.at("grid")[2].get<int>();
      if (merged.is_null()) {
        merged = j;
        merged["probes"] = Json::array();
        total = count;
      } else if (j.at("grid") != merged.at("grid") || j.at("bounds") != merged.at("bounds")) {
        fail(part.string(), "belongs to another grid (its grid or bounds differ)");
      }
      for (const auto& p : j.at("probes")) {
        if (!seen.insert(p.at("linear").get<int>()).second) continue;
        if (!p.contains("skipped") &&
            !fs::is_regular_file(fs::path(dir) / p.at("path").get<std::string>() / "manifest.json"))
          fail(part.string(), fmt::format("lists {} but it is missing", p.at("path").dump()));
        merged["probes"].push_back(p);
      }
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      fail(part.string(), fmt::format("not a shard list: {}", e.what()));
    }
  }
  if (static_cast<int>(seen.size()) != total)
    fail(dir, missingProbesMessage(
                  glm::ivec3(merged.at("grid")[0].get<int>(), merged.at("grid")[1].get<int>(),
                             merged.at("grid")[2].get<int>()),
                  seen, parts, "probes"));
  std::sort(merged["probes"].begin(), merged["probes"].end(),
            [](const Json& a, const Json& b) { return a["linear"] < b["linear"]; });
  const std::string text = merged.dump(2) + "\n";
  writeFileAtomic(fs::path(dir) / "probes.json",
                  std::vector<std::uint8_t>(text.begin(), text.end()));
  if (!global.quiet)
    fmt::print(stderr, "merged {} shard lists into {}: {} probes\n", parts.size(),
               (fs::path(dir) / "probes.json").string(), total);
}

// --merge OUTDIR: a grid's shard lists into probes.json, a volume's shards into its files.
void mergeShards(const std::string& dir, const GlobalOptions& global) {
  const std::vector<fs::path> grid = shardFiles(dir, "probes"), volume = shardFiles(dir, "volume");
  if (grid.empty() && volume.empty())
    fail(dir, "holds no probes.shard-K-of-N.json to merge (nor volume.shard-K-of-N.json)");
  if (!grid.empty()) mergeGridShards(dir, grid, global);
  if (!volume.empty()) mergeVolumeShards(dir, volume, global);
}

void runProbe(const ProbeCliOptions& o, const GlobalOptions& global) {
  if (!o.merge.empty()) {
    if (!o.scene.scene.empty() || !o.at.empty() || !o.grid.empty() || !o.volume.empty())
      failUsage("--merge",
                "merges the lists of a grid's shards, or a volume's shards; it takes no scene, "
                "--at, --grid or --volume");
    mergeShards(o.merge, global);
    return;
  }
  if (o.scene.scene.empty())
    failUsage("scene", "a scene is required (a glTF file, 'sphere', 'grid')");
  if (o.output.empty()) failUsage("--output", "an output directory is required");
  checkVolumeOptions(o);
  if (!o.volume.empty()) {
    runVolume(o, global);
    return;
  }
  if (o.at.empty() == o.grid.empty())
    failUsage(o.at.empty() ? "--at" : "--grid",
              "give either --at X,Y,Z (one probe), --grid with --bounds (a grid of probes) or "
              "--volume with --bounds (an irradiance volume)");
  if (!o.shard.empty() && o.grid.empty())
    failUsage("--shard", "splits a grid or a volume: it needs --grid or --volume");
  if (!o.bounds.empty() && o.grid.empty())
    failUsage("--bounds",
              "is the box of --grid or --volume; one probe (--at) has --proxy and --influence");
  checkSceneOptions(o.scene);
  const glm::vec3 rotation = parseVec3(o.rotation, "--rotation");
  if (rotation != glm::vec3(0.0f) && !o.proxy.starts_with("box:") &&
      !o.influence.starts_with("box:"))
    failUsage("--rotation", "turns the box of --proxy or --influence (box:...); neither is given");
  refuseInputsInside(o.output, sceneInputFiles(o.scene));
  // The output before the scene is read: one probe's directory (empty unless --force), or a
  // grid's, which holds its shards' probes.
  checkBakeOutputDirectory(o.output, o.force || !o.grid.empty());
  Scene scene = loadCaptureScene(o, global);
  const auto [sceneLo, sceneHi] = scene.bounds();
  // The default proxy: the scene's bounds (a room's walls).
  std::optional<ProbeVolume> proxy;
  if (o.proxy != "none")
    proxy = o.proxy.empty()
                ? boxVolume(sceneLo, sceneHi)
                : parseVolume(o.proxy,
                              o.at.empty() ? 0.5f * (sceneLo + sceneHi) : parseVec3(o.at, "--at"),
                              rotation, "--proxy");
  std::vector<PlannedProbe> probes;
  if (!o.at.empty()) {
    PlannedProbe p;
    p.placement.position = parseVec3(o.at, "--at");
    p.placement.hasProxy = proxy.has_value();
    if (proxy) p.placement.proxy = *proxy;
    p.placement.influence = !o.influence.empty() ? parseVolume(o.influence, p.placement.position,
                                                               rotation, "--influence")
                                                 : (proxy ? *proxy : boxVolume(sceneLo, sceneHi));
    p.placement.fade = o.fade >= 0.0f ? o.fade : 0.25f * smallestHalfSize(p.placement.influence);
    p.placement.rotationDegrees = rotation;
    probes.push_back(p);
  } else {
    if (!o.influence.empty())
      failUsage("--influence", "a grid's probes each influence their own cell; use --fade");
    probes = planGrid(o, proxy ? &*proxy : nullptr, rotation);
  }
  // A probe outside the scene sees nothing of it: a mistake, most likely.
  for (const PlannedProbe& p : probes)
    requireInsideScene(p.placement.position, sceneLo, sceneHi, o.at.empty() ? "--bounds" : "--at");
  std::vector<PlannedProbe> mine;
  std::string listName = "probes.json";
  if (!o.shard.empty()) {
    // Neighbours land on different machines, so every shard takes about as long.
    const Shard shard = parseShard(o.shard);
    for (const PlannedProbe& p : probes)
      if (shard.owns(static_cast<std::size_t>(p.linear))) mine.push_back(p);
    listName = shardListName("probes", shard.k, shard.n);
  } else {
    mine = probes;
  }
  for (const PlannedProbe& p : mine)
    checkBakeOutputDirectory(
        p.directory.empty() ? fs::path(o.output) : fs::path(o.output) / p.directory, o.force);
  const LoadedBake env = loadOrBake(o.scene, global);
  scene.lights.insert(scene.lights.end(), env.lights.begin(), env.lights.end());
  const bool showProgress = !global.quiet && ::isatty(STDERR_FILENO);
  const auto start = std::chrono::steady_clock::now();
  // A probe inside geometry sees the inside of a mesh, or nothing: one probe is an error (before
  // the capture, or before anything is written); a grid leaves it out and records why.
  std::map<int, std::string> skipped;
  const auto leaveOut = [&](const PlannedProbe& p, const std::string& reason) {
    const glm::vec3 x = p.placement.position;
    if (o.grid.empty())
      fail(fmt::format("--at {},{},{}", x.x, x.y, x.z),
           fmt::format("the probe is {}; place it in open space", reason));
    skipped[p.linear] = reason;
    if (!global.quiet)
      fmt::print(stderr, "ibl: warning: probe {} at ({:.3g}, {:.3g}, {:.3g}) left out: {}\n",
                 p.directory, x.x, x.y, x.z, reason);
  };
  for (std::size_t i = 0; i < mine.size(); ++i) {
    const PlannedProbe& p = mine[i];
    const std::string inside =
        unusableCaptureReason(inspectCaptureSite(scene, p.placement.position), nullptr);
    if (!inside.empty()) {
      leaveOut(p, inside);
      continue;
    }
    const fs::path dir =
        p.directory.empty() ? fs::path(o.output) : fs::path(o.output) / p.directory;
    const auto t0 = std::chrono::steady_clock::now();
    const CaptureOutcome outcome = captureAndBake(o, scene, env, p, dir, showProgress);
    if (!outcome.unusable.empty()) {
      leaveOut(p, outcome.unusable);
      continue;
    }
    const double totalMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!global.quiet)
      fmt::print(stderr,
                 "[{}/{}] probe at ({:.3g}, {:.3g}, {:.3g}) into {}: capture {:.2f} s, "
                 "bake {:.2f} s\n",
                 i + 1, mine.size(), p.placement.position.x, p.placement.position.y,
                 p.placement.position.z, dir.string(), outcome.milliseconds / 1000.0,
                 (totalMs - outcome.milliseconds) / 1000.0);
  }
  if (!o.grid.empty()) {  // the list last: it names only probes that are complete
    const std::string text = gridListJson(o, mine, skipped).dump(2) + "\n";
    writeFileAtomic(fs::path(o.output) / listName,
                    std::vector<std::uint8_t>(text.begin(), text.end()));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!global.quiet)
      fmt::print(stderr, "{} probes in {:.1f} s ({:.1f} probes per minute){}; list: {}\n",
                 mine.size() - skipped.size(), seconds,
                 60.0 * static_cast<double>(mine.size()) / seconds,
                 skipped.empty() ? "" : fmt::format(", {} left out", skipped.size()),
                 (fs::path(o.output) / listName).string());
  }
}

}  // namespace

bool given(const ProbeCliOptions& o, const std::string& option) {
  const CLI::Option* given = o.command ? o.command->get_option_no_throw(option) : nullptr;
  return given && given->count() > 0;
}

glm::ivec3 parseProbeCounts(const std::string& text, const char* option) {
  const std::vector<float> g = parseNumbers(text, 3, option);
  glm::ivec3 counts;
  for (int i = 0; i < 3; ++i) {
    if (g[i] < 1.0f || g[i] > 64.0f || g[i] != std::floor(g[i]))
      failUsage(option, fmt::format("'{}': each count must be a whole number from 1 to 64", text));
    counts[i] = static_cast<int>(g[i]);
  }
  return counts;
}

std::pair<glm::vec3, glm::vec3> parseBounds(const std::string& text) {
  const std::vector<float> b = parseNumbers(text, 6, "--bounds");
  const glm::vec3 lo(b[0], b[1], b[2]), hi(b[3], b[4], b[5]);
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
    failUsage("--bounds", fmt::format("'{}': an empty box", text));
  return {lo, hi};
}

Scene loadCaptureScene(const ProbeCliOptions& o, const GlobalOptions& global) {
  return withoutObjects(loadScene(o.scene, global), o.exclude, "--exclude");
}

void requireInsideScene(glm::vec3 x, glm::vec3 lo, glm::vec3 hi, const char* option) {
  if (glm::any(glm::lessThan(x, lo)) || glm::any(glm::greaterThan(x, hi)))
    failUsage(option,
              fmt::format("the probe at ({}, {}, {}) lies outside the scene's bounds ({}, {}, {}) "
                          ".. ({}, {}, {})",
                          x.x, x.y, x.z, lo.x, lo.y, lo.z, hi.x, hi.y, hi.z));
}

std::string shardListName(const std::string& stem, int k, int n) {
  return fmt::format("{}.shard-{}-of-{}.json", stem, k, n);
}

std::string missingProbesMessage(glm::ivec3 counts, const std::set<int>& seen,
                                 const std::vector<fs::path>& parts, const std::string& stem) {
  const int nx = counts.x, ny = counts.y;
  const int total = counts.x * counts.y * counts.z;
  std::vector<int> missing;
  for (int l = 0; l < total; ++l)
    if (!seen.count(l)) missing.push_back(l);
  std::string names;
  for (std::size_t i = 0; i < missing.size() && i < 12; ++i)
    names += fmt::format("{}probe_{}_{}_{}", i ? ", " : "", missing[i] % nx, missing[i] / nx % ny,
                         missing[i] / (nx * ny));
  if (missing.size() > 12) names += fmt::format(" and {} more", missing.size() - 12);
  // The shard files' K and N, from their names.
  std::set<int> ns, ks;
  const std::string format = stem + ".shard-%d-of-%d%7s";
  for (const fs::path& part : parts) {
    int k = 0, n = 0;
    char tail[8] = {};
    if (std::sscanf(part.filename().string().c_str(), format.c_str(), &k, &n, tail) == 3 &&
        std::string(tail) == ".json") {
      ns.insert(n);
      ks.insert(k);
    }
  }
  std::string shards;
  if (ns.size() == 1) {
    const int n = *ns.begin();
    std::vector<int> absent;
    for (int k = 0; k < n; ++k)
      if (!ks.count(k)) absent.push_back(k);
    std::string list;
    for (std::size_t i = 0; i < absent.size() && i < 12; ++i)
      list += fmt::format("{}{}/{}", i ? ", " : "", absent[i], n);
    if (absent.size() > 12) list += fmt::format(" and {} more", absent.size() - 12);
    if (absent.size() == 1)
      shards = fmt::format(" (owed by shard {}, which wrote no {})", list,
                           shardListName(stem, absent[0], n));
    else if (!absent.empty())
      shards =
          fmt::format(" (owed by shards {}, which wrote no {}.shard-K-of-{}.json)", list, stem, n);
  }
  return fmt::format(
      "the shards hold {} of the grid's {} probes; missing: {}{}; run the missing "
      "shards again (with the same options), then merge",
      seen.size(), total, names, shards);
}

void addProbeCommand(CLI::App& app, const GlobalOptions& global) {
  auto opts = std::make_shared<ProbeCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "probe",
      "Capture local light probes or an irradiance volume inside a scene (path traced) and bake "
      "them");
  opts->command = cmd;
  cmd->add_option("scene", opts->scene.scene, "glTF file (.gltf, .glb), 'sphere' or 'grid'");
  cmd->add_flag("--strict", opts->scene.strict,
                "Refuse a scene that ibl would render incompletely: a missing or unreadable "
                "texture, an extension ibl does not implement, triangle strips (otherwise "
                "warnings)");
  addVariantOption(cmd, opts->scene);
  cmd->add_option("--env", opts->scene.env,
                  "Distant environment lighting the scene (default: the bundled sunset.exr); "
                  "'none': the scene's lights and emission alone");
  cmd->add_option("--lights", opts->scene.lightsFile, "Lights file (JSON) added to the scene's");
  cmd->add_option("--bake", opts->scene.bakeDir, "An existing bake of the distant environment");
  addEnvScaleOptions(cmd, opts->scene.envScale);
  cmd->add_option("-o,--output", opts->output,
                  "Output directory (created with its missing parents): the probe's bake (--at), "
                  "one directory per probe and probes.json (--grid), or the volume's atlases "
                  "and volume.json (--volume)");
  cmd->add_option("--at", opts->at, "Capture one probe at X,Y,Z");
  cmd->add_option("--grid", opts->grid,
                  "A grid of NX,NY,NZ probes at the cell centers of --bounds");
  cmd->add_option("--bounds", opts->bounds,
                  "The box of the grid or the volume, MINX,MINY,MINZ,MAXX,MAXY,MAXZ");
  addVolumeOptions(cmd, *opts);
  cmd->add_option("--shard", opts->shard,
                  "Capture the K-th of N disjoint parts of the grid or the volume (K/N, K from "
                  "0); merge the parts with --merge");
  cmd->add_option("--merge", opts->merge,
                  "Merge the shards in this directory: a grid's lists into probes.json, a "
                  "volume's into volume.json and its atlases");
  cmd->add_option("--proxy", opts->proxy,
                  "Parallax proxy: sphere:R (about --at), sphere:X,Y,Z,R, "
                  "box:MINX,MINY,MINZ,MAXX,MAXY,MAXZ, or none (default: the scene's bounds)");
  cmd->add_option("--influence", opts->influence,
                  "Where the probe applies, as --proxy (default: the proxy)");
  cmd->add_option("--rotation", opts->rotation,
                  "Rotation of the box volumes about their centers, degrees about X,Y,Z")
      ->capture_default_str();
  cmd->add_option("--fade", opts->fade,
                  "Width of the influence's fade at its border (default: a quarter of its "
                  "smallest half size)")
      ->check(nonNegativeNumber());
  cmd->add_option("--size", opts->capture.size, "Cube face size of the capture and bake")
      ->check(powerOfTwo(8, 1024))
      ->capture_default_str();
  cmd->add_option("--spp", opts->capture.spp, "Path samples per texel")
      ->check(numberIn(1, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--bounces", opts->capture.bounces, "Indirect bounces of the path tracer")
      ->check(numberIn(0, 1000))
      ->capture_default_str();
  cmd->add_flag("--capture-specular", opts->capture.specular,
                "Keep the view-dependent specular of the captured surfaces (default: diffuse "
                "and emission only, as Frostbite captures)");
  cmd->add_option("--seed", opts->capture.seed, "Random seed")->capture_default_str();
  addMultipleScatteringOptions(cmd, opts->scene);
  cmd->add_option("--diffuse", opts->scene.diffuse,
                  "The captured surfaces' diffuse: disney (Frostbite renormalized) or lambert; "
                  "render with the same (recorded in the manifest)")
      ->check(CLI::IsMember({"disney", "lambert"}))
      ->capture_default_str();
  cmd->add_flag("--specular-micro-occlusion", opts->scene.specularMicroOcclusion,
                "Schlick's f90 from F0 in the captured light's bounces, as `ibl render` has it "
                "(recorded in the manifest)");
  cmd->add_option("--exclude", opts->exclude,
                  "Leave glTF nodes (with everything below them) or meshes out of the capture, "
                  "as engines capture the static scene alone: NAME[,NAME...], repeatable; `ibl "
                  "info` lists the names")
      ->delimiter(',');
  cmd->add_flag("--force", opts->force,
                "Replace earlier probes' (or the volume's) files in the output directory");
  cmd->callback([opts, &global] {
    opts->capture.multipleScattering = multipleScatteringChoice(opts->scene);
    opts->capture.diffuse =
        opts->scene.diffuse == "lambert" ? DiffuseModel::Lambert : DiffuseModel::Disney;
    opts->capture.specularMicroOcclusion = opts->scene.specularMicroOcclusion;
    runProbe(*opts, global);
  });
}

}  // namespace ibl::cli
