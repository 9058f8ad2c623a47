#include "ibl/render/probe.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/json_file.hpp"
#include "ibl/shared/sampling.h"
#include "ibl/shared/split_sum.h"
#include "ray_tracer.hpp"

namespace ibl {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

const char* multipleScatteringName(MultipleScattering m) {
  switch (m) {
    case MultipleScattering::Off:
      return "off";
    case MultipleScattering::Scale:
      return "scale";
    case MultipleScattering::Walk:
      break;
  }
  return "walk";
}

Json vec3Json(glm::vec3 v) {
  return Json::array({v.x, v.y, v.z});
}

glm::vec3 vec3Of(const Json& j) {
  if (!j.is_array() || j.size() != 3) throw std::runtime_error("expected [x, y, z]");
  glm::vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = j.at(static_cast<std::size_t>(i)).get<float>();
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw std::runtime_error("a coordinate is not finite");
  return v;
}

Json volumeJson(const ProbeVolume& v, glm::vec3 rotationDegrees) {
  if (v.shape == 0)
    return {{"shape", "sphere"}, {"center", vec3Json(v.center)}, {"radius", v.halfExtent.x}};
  return {{"shape", "box"},
          {"min", vec3Json(v.center - v.halfExtent)},
          {"max", vec3Json(v.center + v.halfExtent)},
          {"rotation_degrees", vec3Json(rotationDegrees)}};
}

ProbeVolume volumeOf(const Json& j, glm::vec3* rotationDegrees) {
  const std::string shape = j.at("shape").get<std::string>();
  if (shape == "sphere") {
    const float r = j.at("radius").get<float>();
    if (!(r > 0.0f) || !std::isfinite(r)) throw std::runtime_error("a sphere's radius must be > 0");
    return sphereVolume(vec3Of(j.at("center")), r);
  }
  if (shape == "box") {
    const glm::vec3 rot =
        j.contains("rotation_degrees") ? vec3Of(j.at("rotation_degrees")) : glm::vec3(0.0f);
    if (rotationDegrees) *rotationDegrees = rot;
    return boxVolume(vec3Of(j.at("min")), vec3Of(j.at("max")), rot);
  }
  throw std::runtime_error(fmt::format("unknown shape '{}'", shape));
}

}  // namespace

ProbeVolume sphereVolume(glm::vec3 center, float radius) {
  ProbeVolume v;
  v.shape = 0;
  v.center = center;
  v.halfExtent = glm::vec3(radius, 0.0f, 0.0f);
  v.worldToLocal = glm::mat3(1.0f);
  return v;
}

ProbeVolume boxVolume(glm::vec3 lo, glm::vec3 hi, glm::vec3 rotationDegrees) {
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
    throw Error(
        fmt::format("box volume: min ({}, {}, {}) must be below max ({}, {}, {}) on every "
                    "axis",
                    lo.x, lo.y, lo.z, hi.x, hi.y, hi.z));
  ProbeVolume v;
  v.shape = 1;
  v.center = 0.5f * (lo + hi);
  v.halfExtent = 0.5f * (hi - lo);
  const glm::vec3 r = glm::radians(rotationDegrees);
  glm::mat4 m(1.0f);
  m = glm::rotate(m, r.z, glm::vec3(0, 0, 1));
  m = glm::rotate(m, r.y, glm::vec3(0, 1, 0));
  m = glm::rotate(m, r.x, glm::vec3(1, 0, 0));
  v.worldToLocal = glm::transpose(glm::mat3(m));  // local-to-world is the rotation
  return v;
}

float volumeSize(const ProbeVolume& v) {
  if (v.shape == 0) return 4.0f / 3.0f * kPi * v.halfExtent.x * v.halfExtent.x * v.halfExtent.x;
  return 8.0f * v.halfExtent.x * v.halfExtent.y * v.halfExtent.z;
}

bool volumeContains(const ProbeVolume& v, glm::vec3 p) {
  if (v.shape == 0) return glm::length(p - v.center) <= v.halfExtent.x;
  const glm::vec3 o = glm::abs(v.worldToLocal * (p - v.center));
  return o.x <= v.halfExtent.x && o.y <= v.halfExtent.y && o.z <= v.halfExtent.z;
}

RenderOptions captureRenderOptions(const CaptureOptions& options, const BakeOptions& bakeOptions) {
  RenderOptions o;
  o.mode = RenderMode::Reference;
  o.spp = options.spp;
  o.bounces = options.bounces;
  o.cameraSeesSpecular = options.specular;
  o.diffuse = options.diffuse;
  o.specularMicroOcclusion = options.specularMicroOcclusion;
  o.captureMetalsAsDiffuse = options.metalsAsDiffuse;
  o.multipleScattering = options.multipleScattering;
  o.cameraSeesEmitters = false;
  o.seed = options.seed;
  o.sheenVisibility = bakeOptions.sheenVisibility;  // the sheen of the bake it lights with
  return o;
}

ProbeCapture captureProbe(const Scene& scene, glm::vec3 position, const BakeResult& bake,
                          const BakeOptions& bakeOptions, const CaptureOptions& options,
                          const std::function<void(float)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  const int n = options.size;
  // The six faces side by side: pixel (x, y) of the strip is texel (x mod n, y) of face x / n,
  // its rays spread over the texel's square on the face plane.
  const RayGenerator faceRays = [&](glm::vec2 pixel) {
    const int face = std::clamp(static_cast<int>(pixel.x) / n, 0, kFaceCount - 1);
    const float sc = 2.0f * (pixel.x - static_cast<float>(face * n)) / static_cast<float>(n) - 1.0f;
    const float tc = 2.0f * pixel.y / static_cast<float>(n) - 1.0f;
    return Ray{position, glm::normalize(faceToDirection(face, sc, tc))};
  };
  RenderOptions o = captureRenderOptions(options, bakeOptions);
  // Premultiplied: a ray that leaves the scene brings nothing; its share is the coverage's.
  o.backgroundEnvironment = false;
  o.backgroundColor = glm::vec3(0.0f);
  const RenderResult strip =
      renderRays(scene, kFaceCount * n, n, faceRays, bake, bakeOptions, o, progress);
  ProbeCapture c;
  c.radiance = CubeMap(n, 1);
  c.coverage = CubeMap(n, 1);
  for (int f = 0; f < kFaceCount; ++f)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        c.radiance.face(0, f).at(x, y) = strip.color.at(f * n + x, y);
        const float covered = strip.alpha[static_cast<std::size_t>(y) * kFaceCount * n + f * n + x];
        c.coverage.face(0, f).at(x, y) = glm::vec3(covered);
      }
  c.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return c;
}

CaptureSite inspectCaptureSite(const Scene& scene, glm::vec3 position, int rays) {
  const RayTracer tracer(scene);
  CaptureSite site;
  int back = 0;
  for (int i = 0; i < rays; ++i) {
    const glm::vec3 d = shared::sphericalFibonacciPoint(i, rays);
    const RayTracer::Hit hit = tracer.intersect(Ray{position, d});
    if (!hit.found) continue;
    site.nearestHit = std::min(site.nearestHit, hit.t);
    if (glm::dot(hit.ng, d) > 0.0f) ++back;
  }
  site.backFaceShare = static_cast<float>(back) / static_cast<float>(rays);
  return site;
}

std::string unusableCaptureReason(const CaptureSite& site, const ProbeCapture* capture) {
  if (site.backFaceShare > 0.5f)
    return fmt::format(
        "inside geometry: {:.0f} % of its rays leave through the back of a face "
        "(the nearest {:.3g} m away)",
        100.0f * site.backFaceShare, site.nearestHit);
  if (capture) {
    float brightest = 0.0f, covered = 0.0f;
    for (const auto& face : capture->radiance.levels[0])
      for (const glm::vec3& p : face.pixels) brightest = std::max({brightest, p.x, p.y, p.z});
    for (const auto& face : capture->coverage.levels[0])
      for (const glm::vec3& p : face.pixels) covered = std::max(covered, p.x);
    if (!(covered > 0.0f))
      return "in the open: it sees none of the scene, only the distant environment";
    if (!(brightest > 0.0f)) return "no light reaches it: every texel of its capture is black";
  }
  return {};
}

std::string captureRecordJson(const CaptureOptions& capture, double captureMilliseconds) {
  const Json j = {{"size", capture.size},
                  {"spp", capture.spp},
                  {"bounces", capture.bounces},
                  {"specular", capture.specular},
                  {"seed", capture.seed},
                  {"milliseconds", std::round(captureMilliseconds)},
                  {"diffuse", capture.diffuse == DiffuseModel::Lambert ? "lambert" : "disney"},
                  {"multiscatter", multipleScatteringName(capture.multipleScattering)},
                  {"specular_micro_occlusion", capture.specularMicroOcclusion}};
  return j.dump();
}

CaptureOptions parseCaptureRecord(const std::string& text, const std::string& name) {
  try {
    const Json c = Json::parse(text);
    // Records from before the shading was written were captured with the defaults.
    CaptureOptions capture;
    capture.multipleScattering = MultipleScattering::Scale;
    const std::string diffuse = c.value("diffuse", "disney");
    if (diffuse != "disney" && diffuse != "lambert")
      throw std::runtime_error(fmt::format("unknown diffuse model '{}'", diffuse));
    capture.diffuse = diffuse == "lambert" ? DiffuseModel::Lambert : DiffuseModel::Disney;
    const std::string ms = c.value("multiscatter", "scale");
    if (ms == "off")
      capture.multipleScattering = MultipleScattering::Off;
    else if (ms == "walk")
      capture.multipleScattering = MultipleScattering::Walk;
    else if (ms != "scale")
      throw std::runtime_error(fmt::format("unknown multiple scattering '{}'", ms));
    capture.specularMicroOcclusion = c.value("specular_micro_occlusion", false);
    // The sampling, as written (a merge of volume shards writes it back).
    capture.size = c.value("size", capture.size);
    capture.spp = c.value("spp", capture.spp);
    capture.bounces = c.value("bounces", capture.bounces);
    capture.specular = c.value("specular", capture.specular);
    capture.seed = c.value("seed", capture.seed);
    return capture;
  } catch (const std::exception& e) {
    fail(name, fmt::format("not a capture record: {}", e.what()));
  }
}

std::string probeRecordJson(const ProbePlacement& p, const CaptureOptions& capture,
                            double captureMilliseconds) {
  Json j;
  j["position"] = vec3Json(p.position);
  j["proxy"] = p.hasProxy ? volumeJson(p.proxy, p.rotationDegrees) : Json(nullptr);
  j["influence"] = volumeJson(p.influence, p.rotationDegrees);
  j["fade"] = p.fade;
  j["capture"] = Json::parse(captureRecordJson(capture, captureMilliseconds));
  j["conventions"] = {
      {"lookup",
       "parallax-corrected along the proxy (Lagarde & Zanuttini 2012), blended back "
       "toward the reflection by roughness; distance-based roughness (Frostbite, "
       "appendix F)"},
      {"composition",
       "smallest influence first, share = saturate(weight - coverage), then the "
       "distant environment (Frostbite 4.9.5)"},
      {"coverage",
       "the radiance is premultiplied (what the scene's surfaces send; the distant environment "
       "seen directly left out); coverage_specular.ktx2 and coverage_irradiance.ktx2 hold the "
       "share of each texel that meets the scene, filtered as the specular chain and the "
       "irradiance: the alpha of each lookup (Frostbite 4.9.5)"}};
  return j.dump();
}

ProbePlacement parseProbeRecord(const std::string& text, const std::string& name,
                                CaptureOptions* capture) {
  try {
    const Json j = Json::parse(text);
    if (capture)
      *capture = j.contains("capture") ? parseCaptureRecord(j.at("capture").dump(), name)
                                       : parseCaptureRecord("{}", name);
    ProbePlacement p;
    p.position = vec3Of(j.at("position"));
    if (!j.at("proxy").is_null()) {
      p.proxy = volumeOf(j.at("proxy"), &p.rotationDegrees);
      p.hasProxy = true;
    }
    p.influence = volumeOf(j.at("influence"), &p.rotationDegrees);
    p.fade = j.at("fade").get<float>();
    if (!(p.fade >= 0.0f) || !std::isfinite(p.fade)) throw std::runtime_error("fade must be >= 0");
    return p;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail(name, fmt::format("not a probe record: {}", e.what()));
  }
}

std::string captureShadingMismatch(const CaptureOptions& c, const RenderOptions& r) {
  std::string out;
  const auto add = [&](std::string_view what, std::string_view captured, std::string_view here) {
    if (captured == here) return;
    out += fmt::format("{}{}: {} in the capture, {} here", out.empty() ? "" : "; ", what, captured,
                       here);
  };
  const auto diffuseName = [](DiffuseModel m) {
    return m == DiffuseModel::Lambert ? "lambert" : "disney";
  };
  add("diffuse", diffuseName(c.diffuse), diffuseName(r.diffuse));
  const auto onOff = [](bool on) { return on ? "on" : "off"; };
  add("multiple scattering", onOff(c.multipleScattering != MultipleScattering::Off),
      onOff(r.multipleScattering != MultipleScattering::Off));
  add("specular micro-occlusion", onOff(c.specularMicroOcclusion), onOff(r.specularMicroOcclusion));
  return out;
}

void checkCaptureShading(const CaptureOptions& capture, const std::string& name,
                         const RenderOptions& render, bool force,
                         const std::function<void(const std::string&)>& warn) {
  const std::string mismatch = captureShadingMismatch(capture, render);
  if (mismatch.empty()) return;
  const std::string message = fmt::format(
      "{}: captured with another shading ({}): capture it again with the same "
      "options{}",
      name, mismatch, force ? "" : ", or give --force to use it anyway");
  if (!force) throw Error(message);
  if (warn) warn(message);
}

void checkProbeShading(const std::vector<LocalProbe>& probes, const RenderOptions& render,
                       bool force, const std::function<void(const std::string&)>& warn) {
  for (const LocalProbe& p : probes) checkCaptureShading(p.capture, p.path, render, force, warn);
}

LocalProbe bakeProbe(const ProbeCapture& capture, const ProbePlacement& placement,
                     const CaptureOptions& captureOptions, const BakeOptions& options) {
  const auto bakeCube = [&](const CubeMap& cube) {
    Environment e;
    e.layout = Layout::Cube;
    e.cube = cube;
    return bakeEnvironment(e, options);
  };
  LocalProbe probe;
  probe.placement = placement;
  probe.capture = captureOptions;
  probe.options = options;
  probe.bake = bakeCube(capture.radiance);
  BakeResult coverage = bakeCube(capture.coverage);
  probe.coverageSpecular = std::move(coverage.specular);
  probe.coverageIrradiance = std::move(coverage.irradiance);
  return probe;
}

namespace {

LocalProbe loadProbe(const fs::path& dir) {
  const fs::path manifestPath = dir / "manifest.json";
  if (!fs::is_regular_file(manifestPath))
    fail(dir.string(), "is not a probe directory (no manifest.json)");
  const Json manifest = readJsonFile(manifestPath);
  if (!manifest.contains("probe"))
    fail(manifestPath.string(),
         "has no probe record: a bake of a distant environment, not a probe "
         "(bake probes with `ibl probe`)");
  LocalProbe probe;
  probe.placement =
      parseProbeRecord(manifest["probe"].dump(), manifestPath.string(), &probe.capture);
  probe.bake = loadBake(dir, &probe.options);
  // Probes from before the coverage was written hold the distant environment in their radiance:
  // coverage 1 everywhere, as they were composed then.
  if (fs::is_regular_file(dir / "coverage_specular.ktx2")) {
    probe.coverageSpecular = readBakedCube(dir / "coverage_specular.ktx2");
    probe.coverageIrradiance = readBakedCube(dir / "coverage_irradiance.ktx2");
    if (probe.coverageSpecular.levelCount() != probe.bake.specular.levelCount() ||
        probe.coverageSpecular.size() != probe.bake.specular.size() ||
        probe.coverageIrradiance.size() != probe.bake.irradiance.size())
      fail((dir / "coverage_specular.ktx2").string(),
           "does not match the probe's specular chain and irradiance in size and levels");
  }
  probe.path = dir.string();
  return probe;
}

}  // namespace

std::vector<LocalProbe> loadProbes(const std::vector<std::string>& paths) {
  std::vector<LocalProbe> probes;
  for (const std::string& path : paths) {
    const fs::path dir(path);
    if (!fs::exists(dir)) fail(path, "no such probe directory");
    if (fs::is_regular_file(dir / "probes.json")) {  // a grid: every probe it lists
      const Json grid = readJsonFile(dir / "probes.json");
      try {
        for (const auto& entry : grid.at("probes"))
          if (!entry.contains("skipped"))  // a probe left out of the capture (ibl probe)
            probes.push_back(loadProbe(dir / entry.at("path").get<std::string>()));
      } catch (const Error&) {
        throw;
      } catch (const std::exception& e) {
        fail((dir / "probes.json").string(), fmt::format("not a probe grid: {}", e.what()));
      }
    } else {
      probes.push_back(loadProbe(dir));
    }
  }
  std::stable_sort(probes.begin(), probes.end(), [](const LocalProbe& a, const LocalProbe& b) {
    return volumeSize(a.placement.influence) < volumeSize(b.placement.influence);
  });
  return probes;
}

ProbeLighting lookupProbes(const std::vector<LocalProbe>& probes, glm::vec3 position,
                           glm::vec3 reflection, glm::vec3 diffuseDirection, float roughness,
                           const RenderOptions& o) {
  ProbeLighting result;
  const bool wantSpecular = o.only != ShadingTerms::Diffuse;
  const bool wantDiffuse = o.only != ShadingTerms::Specular;
  for (const LocalProbe& probe : probes) {
    if ((!wantSpecular || result.coverage >= 1.0f) &&
        (!wantDiffuse || result.diffuseCoverage >= 1.0f))
      break;
    const ProbePlacement& pl = probe.placement;
    const float weight = shared::influenceWeight(pl.influence, pl.fade, position);
    const float share = shared::probeShare(weight, result.coverage);
    const float diffuseShare = shared::probeShare(weight, result.diffuseCoverage);
    if (share <= 0.0f && diffuseShare <= 0.0f) continue;
    const bool covered = !probe.coverageSpecular.levels.empty();
    shared::ParallaxLookup look;
    look.direction = reflection;
    look.roughness = roughness;
    if (pl.hasProxy && o.parallaxCorrection)
      look = shared::parallaxCorrectedLookup(pl.proxy, pl.position, position, reflection, roughness,
                                             o.distanceRoughness);
    if (wantSpecular && share > 0.0f) {
      const float lod = specularLodForRoughness(look.roughness, probe.bake.specular.levelCount(),
                                                probe.options.specular.mapping);
      result.prefiltered += share * sampleTrilinear(probe.bake.specular, lod, look.direction);
      const float alpha =
          covered ? sampleTrilinear(probe.coverageSpecular, lod, look.direction).x : 1.0f;
      result.coverage = shared::coverageAfterProbe(result.coverage, share, alpha);
    }
    if (wantDiffuse && diffuseShare > 0.0f) {
      result.irradiance +=
          diffuseShare * sampleBilinear(probe.bake.irradiance, 0, diffuseDirection);
      const float alpha =
          covered ? sampleBilinear(probe.coverageIrradiance, 0, diffuseDirection).x : 1.0f;
      result.diffuseCoverage =
          shared::coverageAfterProbe(result.diffuseCoverage, diffuseShare, alpha);
    }
  }
  return result;
}

}  // namespace ibl
