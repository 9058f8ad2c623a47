#pragma once
// API: internal (may change without notice; the irradiance volume of the front end and the viewer)
// Irradiance volumes: a grid of probes captured inside the scene by the path tracer, each with
// its irradiance and the moments of its distance to the first surface in octahedral maps, read
// with trilinear, backface and visibility weights (Majercik et al. 2019; the lookup's math is
// ibl/shared/irradiance_volume.h, the file layout docs/probes.md, "Irradiance volumes").
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "ibl/core/image.hpp"
#include "ibl/render/ambient_occlusion.hpp"
#include "ibl/render/probe.hpp"
#include "ibl/shared/irradiance_volume.h"

namespace ibl {

using shared::VolumeGrid;

// The resolution of a volume's maps and the lookup's bias.
struct VolumeOptions {
  int captureSize = 32;      // octahedral map of radiance and distance traced per probe, per side
  int irradianceTexels = 8;  // the stored irradiance tile's interior, per side
  int distanceTexels = 16;   // the stored distance tile's interior, per side
  int distanceRays = 4;      // rays per captured texel for the distances
  // Majercik et al. 2019's listing: (0.2 n + 0.8 v) x 0.75 x 0.3 of the smallest spacing.
  float normalBias = 0.045f;
  float viewBias = 0.18f;
};

// Probes at the cell centers of `counts` cells over the box [lo, hi]; throws on an empty box or
// a count outside [1, 64].
VolumeGrid volumeGrid(glm::vec3 lo, glm::vec3 hi, glm::ivec3 counts, const VolumeOptions& options);
int volumeProbeCount(const VolumeGrid& grid);
// Probe `index`'s position on the grid (before relocation).
glm::vec3 volumeProbePosition(const VolumeGrid& grid, int index);

// Where a probe goes after relocation (Majercik et al. 2021, "Scaling Probe-Based Real-Time
// Dynamic Global Illumination for Production", JCGT 10(2), section 5.2): out of the geometry it
// landed in, through the nearest back face, and away from a surface nearer than a fifth of the
// spacing; at most 0.45 of the spacing from its grid position on each axis. A probe still
// inside is switched off (`on` false, `reason` says why).
struct ProbeRelocation {
  glm::vec3 offset{0.0f};
  bool on = true;
  std::string reason;  // empty when on
};
ProbeRelocation relocateProbe(const Scene& scene, glm::vec3 position, glm::vec3 spacing);
// relocateProbe for the probes `which` (linear indices) of `grid`, in parallel over one ray
// tracer of the scene; by position in `which`.
std::vector<ProbeRelocation> relocateProbes(const Scene& scene, const VolumeGrid& grid,
                                            const std::vector<int>& which);

// A volume: the grid, its atlases and each probe's record.
struct IrradianceVolume {
  VolumeGrid grid{};
  glm::vec3 boundsLo{0.0f}, boundsHi{0.0f};  // the box the cells fill (--bounds)
  VolumeOptions options;
  CaptureOptions capture;  // the path tracer's shading (as a probe's)
  // Tile per probe (ibl/shared/irradiance_volume.h): RGB the irradiance over pi (E / pi, as
  // the bakes' irradiance maps), and R, G the mean and mean squared distance (B 0).
  Image irradiance, distance;
  std::vector<ProbeRelocation> probes;  // per probe, by linear index
  std::vector<bool> captured;           // per probe: its tiles hold a capture (a shard's own)
  double captureMilliseconds = 0.0;
  std::string path;  // where it was read from
};

// An empty volume over the box: its atlases sized and black, every probe on and uncaptured.
IrradianceVolume makeVolume(glm::vec3 lo, glm::vec3 hi, glm::ivec3 counts,
                            const VolumeOptions& options, const CaptureOptions& capture);

// The probes' relocation records as the lookup reads them: xyz the offset, w 1 when on.
std::vector<glm::vec4> relocationRecords(const IrradianceVolume& volume);

// Captures the probes `which` (linear indices; their relocation already set) with the reference
// path tracer (the environment of `bake`, the scene's emission, the lights' light on the
// surfaces, not the lights seen directly: the split sum adds those analytically), writing their
// tiles: the irradiance from the radiance map by cosine-weighted quadrature over its texels'
// solid angles, the distance moments by the paper's cos^50 lobe. progress: 0 to 1.
void captureVolumeProbes(const Scene& scene, IrradianceVolume& volume,
                         const std::vector<int>& which, const BakeResult& bake,
                         const BakeOptions& bakeOptions,
                         const std::function<void(float)>& progress = {});

// The solid angle of texel (x, y) of an octahedral map of size x size texels, steradians: the
// map's Jacobian 1 / |q|^3 (q the point on the octahedron |x| + |y| + |z| = 1) integrated over
// the texel.
double octahedralTexelSolidAngle(int x, int y, int size);

// Fills the border of every tile of an atlas from its interior (volumeBorderSource).
void fillVolumeBorders(Image& atlas, const VolumeGrid& grid, int texels);

// An atlas read bilinearly at a point in texels (volumeAtlasTexel).
glm::vec3 sampleVolumeAtlas(const Image& atlas, glm::vec2 texel);

// The volume's irradiance over pi at p: normal n, unit direction v toward the viewer, the
// diffuse lookup direction `diffuseDirection` (ibl/shared/irradiance_volume.h's loop).
glm::vec3 lookupVolume(const IrradianceVolume& volume, glm::vec3 p, glm::vec3 n, glm::vec3 v,
                       glm::vec3 diffuseDirection);

// Writes irradiance.ktx2, distance.ktx2 (RGBA32F 2D atlases) and volume.json into `dir`, all
// or none; `stem` other than "volume" names a shard's files (STEM.json, and the atlases'
// names with its suffix).
void writeVolume(const IrradianceVolume& volume, const std::filesystem::path& dir,
                 const std::string& stem = "volume");
// The names of the files writeVolume writes with `stem`: the manifest, the irradiance atlas and
// the distance atlas.
std::vector<std::string> volumeFileNames(const std::string& stem = "volume");

// Reads a volume written by writeVolume (dir, or the manifest's path); throws Error naming the
// file for anything missing, malformed or inconsistent.
IrradianceVolume loadVolume(const std::filesystem::path& path, const std::string& stem = "volume");

// The live update (Majercik et al. 2019, section 5), one frame: from every probe that is on,
// `raysPerProbe` rays along volumeRayDirection under a rotation drawn for `frame`; a ray's
// radiance is what the split sum's diffuse gives its hit (the lights with ray-traced shadows,
// the distant environment and this volume itself before the frame, so that bounces accumulate
// over frames; metals seen as the capture sees them), or the environment where it leaves; each
// texel is then blended with volumeBlend (irradiance by the cosine, distances by the cos^50
// lobe, as a capture filters them).
// A texel of direction `normal` as a cosine-lobe filter of samples over the sphere (Majercik et
// al. 2019, section 4.1): over the samples on normal's side, the sums of w_i cos^power(theta_i)
// value_i and of w_i cos^power(theta_i), w_i the sample's own weight (a captured texel's solid
// angle; 1 for every ray when `weights` is empty). The capture and the update divide the one by
// the other: power 1 gives the irradiance over pi, kVolumeDistanceSharpness the distance moments.
struct LobeSums {
  glm::dvec3 weighted{0.0};
  double total = 0.0;
};
LobeSums cosineLobeSums(glm::vec3 normal, std::span<const glm::vec3> directions,
                        std::span<const float> weights, std::span<const glm::vec3> values,
                        double power);

// The rotation of frame `frame`'s rays (volumeRayDirection), drawn uniformly from `seed` and the
// frame: the CPU's update and the viewer's turn the same rays.
glm::mat3 volumeFrameRotation(unsigned seed, unsigned frame);

struct VolumeUpdateOptions {
  int raysPerProbe = 256;
  float hysteresis = 0.9f;  // the share of a texel kept per frame
};
void updateVolume(const Scene& scene, IrradianceVolume& volume, const BakeResult& bake,
                  const BakeOptions& bakeOptions, const RenderOptions& shading,
                  const VolumeUpdateOptions& options, unsigned frame);

// The screen-space occlusion's settings under a volume: its default radius (0) becomes half the
// volume's smallest spacing, so that it darkens only what the probes cannot resolve (the
// occluders nearer than a cell), not what the volume's visibility already holds; a radius the
// user gave is kept. Without a volume, the settings as given.
ScreenAmbientOcclusionSettings occlusionUnderVolume(const ScreenAmbientOcclusionSettings& settings,
                                                    const IrradianceVolume* volume);

// Copies probe `index`'s tiles from one volume into another of the same grid.
void copyVolumeProbe(const IrradianceVolume& from, IrradianceVolume& to, int index);

}  // namespace ibl
