#pragma once
// `ibl probe`'s options and what its two halves share: local probes, one or a grid (probe.cpp),
// and the irradiance volume (probe_volume.cpp).
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/vec3.hpp>

#include "commands.hpp"
#include "ibl/render/probe.hpp"
#include "scene_options.hpp"

namespace ibl::cli {

struct ProbeCliOptions {
  SceneCliOptions scene;  // scene, --env, --lights, --spot-lumens
  std::string output;
  std::string at;
  std::string proxy;      // sphere:R | sphere:X,Y,Z,R | box:MINX,MINY,MINZ,MAXX,MAXY,MAXZ | none
  std::string influence;  // the same forms; default: the proxy (a grid: each probe's cell)
  std::string rotation = "0,0,0";
  float fade = -1.0f;  // default: a quarter of the influence's smallest half size
  std::string grid, bounds, shard;
  std::string merge;
  CaptureOptions capture;
  std::vector<std::string> exclude;  // glTF node or mesh names left out of the capture
  bool force = false;
  // --volume NX,NY,NZ: an irradiance volume over --bounds (probe_volume.cpp).
  std::string volume;
  int volumeSize = 32;    // --volume-size: the octahedral map traced per probe, per side
  int volumeTexels = 8;   // --volume-texels: the irradiance tile's interior (distance: twice)
  float normalBias = -1;  // --normal-bias, --view-bias; < 0: VolumeOptions' defaults
  float viewBias = -1;
  const CLI::App* command = nullptr;  // the subcommand, for which options were given
};

// Whether `option` ("--size") was on the command line.
bool given(const ProbeCliOptions& o, const std::string& option);

// --grid and --volume: NX,NY,NZ, each a whole number from 1 to 64; a usage error naming `option`.
glm::ivec3 parseProbeCounts(const std::string& text, const char* option);
// --bounds: MINX,MINY,MINZ,MAXX,MAXY,MAXZ, a usage error for an empty box.
std::pair<glm::vec3, glm::vec3> parseBounds(const std::string& text);

// The scene the probes see: the scene's and --lights' without --exclude's objects (dynamic
// objects left out: engines capture the static scene alone).
Scene loadCaptureScene(const ProbeCliOptions& o, const GlobalOptions& global);

// A usage error naming `option` when a probe at `x` lies outside the scene's bounds [lo, hi]:
// it would see nothing of the scene, a mistake most likely.
void requireInsideScene(glm::vec3 x, glm::vec3 lo, glm::vec3 hi, const char* option);

// The file a shard K/N writes its part of a grid or volume into: "STEM.shard-K-of-N.json".
std::string shardListName(const std::string& stem, int k, int n);

// What a merge lacks: the probes of a grid of `counts` that no shard holds (`seen`: the linear
// indices present; named probe_I_J_K, at most a dozen) and, when the shard files `parts` present
// (STEM.shard-K-of-N.json) are all of one N, the shards K/N that wrote none, to run again.
std::string missingProbesMessage(glm::ivec3 counts, const std::set<int>& seen,
                                 const std::vector<std::filesystem::path>& parts,
                                 const std::string& stem);

// The options of an irradiance volume (--volume-size, --volume-texels, --normal-bias,
// --view-bias), registered on `cmd`.
void addVolumeOptions(CLI::App* cmd, ProbeCliOptions& o);
// Usage errors for the volume's options without --volume (`volume` false), or for the options
// that contradict it (with --volume).
void checkVolumeOptions(const ProbeCliOptions& o);
// `ibl probe SCENE --volume NX,NY,NZ --bounds BOX -o DIR [--shard K/N]`.
void runVolume(const ProbeCliOptions& o, const GlobalOptions& global);
// --merge DIR: the volume shards `parts` (volume.shard-K-of-N.json, sorted) into DIR's volume.
void mergeVolumeShards(const std::filesystem::path& dir,
                       const std::vector<std::filesystem::path>& parts,
                       const GlobalOptions& global);

}  // namespace ibl::cli
