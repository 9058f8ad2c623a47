#pragma once
// API: internal (may change without notice; local probes of the front end and the viewer)
// Local light probes: cube maps captured inside the scene by the path tracer and baked like an
// environment, then looked up with parallax correction and blended by influence volumes
// (Lagarde & de Rousiers 2014, section 4.9; the formulas are ibl/shared/probes.h).
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "ibl/bake/bake.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/render/scene.hpp"
#include "ibl/shared/probes.h"

namespace ibl {

using shared::ProbeVolume;

// A sphere of `radius` about `center`.
ProbeVolume sphereVolume(glm::vec3 center, float radius);
// The box [lo, hi] (in its own axes), turned about its center by Euler angles in degrees
// (about X, then Y, then Z). Throws when lo >= hi on an axis.
ProbeVolume boxVolume(glm::vec3 lo, glm::vec3 hi, glm::vec3 rotationDegrees = glm::vec3(0.0f));
// Its volume (for the composition order).
float volumeSize(const ProbeVolume& v);
// Whether p lies inside (or on) the volume.
bool volumeContains(const ProbeVolume& v, glm::vec3 p);

// Where a probe was captured and how it applies.
struct ProbePlacement {
  glm::vec3 position{0.0f};         // capture point (the cube map's center)
  bool hasProxy = false;            // without a proxy the probe is a distant one (no parallax)
  ProbeVolume proxy{};              // the scene's shape for parallax correction
  ProbeVolume influence{};          // where the probe applies
  float fade = 0.0f;                // width of the influence's border over which it fades out
  glm::vec3 rotationDegrees{0.0f};  // of the box volumes (as given), for the manifest
};

struct CaptureOptions {
  int size = 128;         // cube face size of the capture
  int spp = 64;           // path samples per texel
  int bounces = 4;        // indirect bounces of the path tracer
  bool specular = false;  // keep the view-dependent specular of the surfaces the probe sees
  // The material model of the path tracer (RenderOptions): a capture lit with one model and
  // rendered with another is a different material on either side of the probe.
  DiffuseModel diffuse = DiffuseModel::Disney;
  bool specularMicroOcclusion = false;
  // A metal seen by the probe as a diffuse surface of albedo F0 (RenderOptions); false: black.
  bool metalsAsDiffuse = true;
  // The path tracer's multiple scattering between microfacets (RenderOptions).
  MultipleScattering multipleScattering = MultipleScattering::Walk;
  unsigned seed = 1;
};

// A capture as Frostbite stores it (Lagarde & de Rousiers 2014, 4.9.1.2 and 4.9.5): the light
// the scene's surfaces send, premultiplied by the share of each texel they cover, and that share
// (the alpha), so that where the probe sees the distant environment (a window, an open roof) the
// next probe or the distant environment, seen from the shaded point, fills in.
struct ProbeCapture {
  CubeMap radiance;  // one level, premultiplied: the distant environment seen directly left out
  CubeMap coverage;  // one level, RGB = the share of each texel whose rays meet the scene
  double milliseconds = 0.0;
};

// Renders the cube at `position` with the reference path tracer (the environment of `bake`, the
// scene's lights and emission), texel by texel over the same area as the cube's texels. The
// surfaces the probe sees keep their diffuse light and emission alone (unless
// options.specular), and a metal is seen as a diffuse surface of albedo F0 (4.9.1.2): its
// specular depends on the view, and it would otherwise be black.
ProbeCapture captureProbe(const Scene& scene, glm::vec3 position, const BakeResult& bake,
                          const BakeOptions& bakeOptions, const CaptureOptions& options,
                          const std::function<void(float)>& progress = {});

// How a capture point sits in the scene, from rays cast evenly over the sphere of directions:
// the share whose first hit is the back of a face (the inside of a closed mesh) and the
// distance to the nearest hit. A probe inside geometry sees only the inside of a mesh: black,
// or its own back faces; renders would read that as the room's light.
struct CaptureSite {
  float backFaceShare = 0.0f;  // in [0, 1]
  float nearestHit = INFINITY;
};
CaptureSite inspectCaptureSite(const Scene& scene, glm::vec3 position, int rays = 512);

// Why a capture must not be used: most of its rays leave through back faces (inside
// geometry), or no light reached it (every texel black); empty when it is sound. `position`
// names the probe in the message.
std::string unusableCaptureReason(const CaptureSite& site, const ProbeCapture* capture);

// The reference's options for a capture with `options`, lit by a bake made with `bakeOptions`:
// the camera does not see the lights (the split sum adds them), nor, unless options.specular,
// the surfaces' specular.
RenderOptions captureRenderOptions(const CaptureOptions& options, const BakeOptions& bakeOptions);

// The manifests' "capture" record (a JSON object as text) and back; a record without the
// shading's fields gets the defaults it was captured with. `name` names the file in errors.
std::string captureRecordJson(const CaptureOptions& capture, double captureMilliseconds);
CaptureOptions parseCaptureRecord(const std::string& json, const std::string& name);

// The manifest's "probe" record (a JSON object as text) and back; `name` names the file in
// errors. `capture` receives the capture's options (its shading; a record from before they were
// written gets the defaults it was captured with).
std::string probeRecordJson(const ProbePlacement& placement, const CaptureOptions& capture,
                            double captureMilliseconds);
ProbePlacement parseProbeRecord(const std::string& json, const std::string& name,
                                CaptureOptions* capture = nullptr);

// How the capture's shading differs from a render's (the diffuse model, multiple scattering on
// or off, the specular micro-occlusion), as "diffuse: disney in the capture, lambert here; ...";
// empty when they agree. The reference's random walk and the split sum's compensation are the
// same material.
std::string captureShadingMismatch(const CaptureOptions& capture, const RenderOptions& render);

// A baked probe, ready to shade with.
struct LocalProbe {
  ProbePlacement placement;
  CaptureOptions capture;  // the shading it was captured with
  BakeResult bake;         // of the premultiplied radiance
  BakeOptions options;
  // The capture's coverage filtered as the specular chain (every level) and as the irradiance:
  // the alpha of each lookup. Empty for probes from before they were written (coverage 1).
  CubeMap coverageSpecular, coverageIrradiance;
  std::string path;
};

// Bakes a capture into a probe as `ibl probe` does: the premultiplied radiance and the coverage,
// each through bakeEnvironment with `options` (the coverage's specular chain and irradiance are
// the alpha of the probe's lookups).
LocalProbe bakeProbe(const ProbeCapture& capture, const ProbePlacement& placement,
                     const CaptureOptions& captureOptions, const BakeOptions& options);

// Reads probe directories (each written by `ibl probe`, or a grid's directory with its
// probes.json), sorted from the smallest influence volume to the largest.
std::vector<LocalProbe> loadProbes(const std::vector<std::string>& paths);

// Throws, naming `name` (the file it was read from), when a capture (a probe's, an irradiance
// volume's) was made with another shading than `render`'s (captureShadingMismatch); with
// `force`, warns through `warn` instead.
void checkCaptureShading(const CaptureOptions& capture, const std::string& name,
                         const RenderOptions& render, bool force,
                         const std::function<void(const std::string&)>& warn);
// checkCaptureShading for each probe, naming it.
void checkProbeShading(const std::vector<LocalProbe>& probes, const RenderOptions& render,
                       bool force, const std::function<void(const std::string&)>& warn);

// What the probes give a point: the specular map's value along the (parallax-corrected)
// reflection and the irradiance (E / pi), each already weighed by the probes' shares, and the
// coverage the probes reached for each (the distant environment gets the rest).
struct ProbeLighting {
  glm::vec3 prefiltered{0.0f};
  glm::vec3 irradiance{0.0f};
  float coverage = 0.0f;         // of the specular
  float diffuseCoverage = 0.0f;  // of the irradiance
};
// position, normal, the dominant reflection r and diffuse directions, perceptual roughness.
ProbeLighting lookupProbes(const std::vector<LocalProbe>& probes, glm::vec3 position,
                           glm::vec3 reflection, glm::vec3 diffuseDirection, float roughness,
                           const RenderOptions& options);

}  // namespace ibl
