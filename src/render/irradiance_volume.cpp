#include "ibl/render/irradiance_volume.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/json_file.hpp"
#include "ibl/io/ktx2.hpp"
#include "ray_tracer.hpp"

namespace ibl {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

glm::ivec2 atlasSize(const VolumeGrid& g, int texels) {
  return {g.counts.x * g.counts.y * (texels + 2), g.counts.z * (texels + 2)};
}

// The top-left texel of probe `index`'s tile.
glm::ivec2 tileOrigin(const VolumeGrid& g, int index, int texels) {
  const int perRow = g.counts.x * g.counts.y;
  return glm::ivec2(index % perRow, index / perRow) * (texels + 2);
}

// The direction at the center of texel (x, y) of an octahedral map of size texels per side.
glm::vec3 octahedralTexelDirection(float x, float y, int size) {
  const float s = static_cast<float>(size);
  return shared::octahedralDecode({2.0f * x / s - 1.0f, 2.0f * y / s - 1.0f});
}

// What the rays from a point meet: the share that leave through back faces, and the nearest
// back and front faces.
struct SiteRays {
  float backShare = 0.0f;
  float nearestBack = INFINITY, nearestFront = INFINITY;
  glm::vec3 towardBack{0.0f}, towardFront{0.0f};
};

SiteRays traceSite(const RayTracer& tracer, glm::vec3 p, int rays) {
  SiteRays s;
  int back = 0;
  for (int i = 0; i < rays; ++i) {
    const glm::vec3 d = shared::sphericalFibonacciPoint(i, rays);
    const RayTracer::Hit hit = tracer.intersect(Ray{p, d});
    if (!hit.found) continue;
    if (glm::dot(hit.ng, d) > 0.0f) {
      ++back;
      if (hit.t < s.nearestBack) s.nearestBack = hit.t, s.towardBack = d;
    } else if (hit.t < s.nearestFront) {
      s.nearestFront = hit.t, s.towardFront = d;
    }
  }
  s.backShare = static_cast<float>(back) / static_cast<float>(rays);
  return s;
}

// The share of back-face hits above which a probe is inside geometry (the paper's 25 %).
constexpr float kInsideShare = 0.25f;

Json vec3Json(glm::vec3 v) {
  return Json::array({v.x, v.y, v.z});
}

glm::vec3 vec3From(const Json& j) {
  if (!j.is_array() || j.size() != 3) throw std::runtime_error("expected [x, y, z]");
  const glm::vec3 v(j[0].get<float>(), j[1].get<float>(), j[2].get<float>());
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw std::runtime_error("a coordinate is not finite");
  return v;
}

std::string atlasName(const std::string& base, const std::string& stem) {
  return stem == "volume" ? base + ".ktx2" : fmt::format("{}.{}.ktx2", base, stem);
}

Ktx2Texture atlasTexture(const Image& atlas) {
  Ktx2Texture t;
  t.format = PixelFormat::Rgba32f;
  t.faceCount = 1;
  t.levels = {{atlas}};
  return t;
}

Image readAtlas(const fs::path& path, glm::ivec2 size) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  Ktx2Texture t = decodeKtx2(bytes, path.string());
  if (t.faceCount != 1 || t.levels.empty() || t.levels[0].size() != 1)
    fail(path.string(), "is not a 2D atlas (one face, one level)");
  Image image = std::move(t.levels[0][0]);
  if (image.width != size.x || image.height != size.y)
    fail(path.string(), fmt::format("is {} x {}; the manifest's grid needs {} x {}", image.width,
                                    image.height, size.x, size.y));
  for (const glm::vec3& p : image.pixels)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail(path.string(), "holds a texel that is not finite (NaN or infinity)");
  return image;
}

}  // namespace

VolumeGrid volumeGrid(glm::vec3 lo, glm::vec3 hi, glm::ivec3 counts, const VolumeOptions& o) {
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
    throw Error("volume: an empty box (min must be below max on every axis)");
  for (int i = 0; i < 3; ++i)
    if (counts[i] < 1 || counts[i] > 64)
      throw Error("volume: each probe count must be a whole number from 1 to 64");
  VolumeGrid g{};
  g.spacing = (hi - lo) / glm::vec3(counts);
  g.origin = lo + 0.5f * g.spacing;
  g.counts = counts;
  g.normalBias = o.normalBias;
  g.viewBias = o.viewBias;
  g.irradianceTexels = o.irradianceTexels;
  g.distanceTexels = o.distanceTexels;
  g.rules = shared::kVolumeAllRules;
  return g;
}

int volumeProbeCount(const VolumeGrid& g) {
  return g.counts.x * g.counts.y * g.counts.z;
}

glm::vec3 volumeProbePosition(const VolumeGrid& g, int index) {
  return shared::volumeGridPosition(g, index);
}

namespace {

ProbeRelocation relocateWith(const RayTracer& tracer, glm::vec3 position, glm::vec3 spacing) {
  const float unit = std::min(spacing.x, std::min(spacing.y, spacing.z));
  const float minFront = 0.2f * unit;
  const glm::vec3 limit = 0.45f * spacing;
  constexpr int kRays = 256;
  ProbeRelocation r;
  for (int iteration = 0; iteration < 8; ++iteration) {
    const SiteRays s = traceSite(tracer, position + r.offset, kRays);
    glm::vec3 step(0.0f);
    if (s.backShare > kInsideShare && std::isfinite(s.nearestBack))
      step = s.towardBack * (s.nearestBack + 0.5f * minFront);  // out through the back face
    else if (s.nearestFront < minFront)
      step = -s.towardFront * (minFront - s.nearestFront);  // away from the wall
    else
      break;
    r.offset = glm::clamp(r.offset + step, -limit, limit);
  }
  const SiteRays s = traceSite(tracer, position + r.offset, kRays);
  if (s.backShare > kInsideShare) {
    r.on = false;
    r.reason = fmt::format(
        "inside geometry: {:.0f} % of its rays leave through the back of a face, and no "
        "position within 0.45 of the spacing gets it out",
        100.0f * s.backShare);
  }
  return r;
}

}  // namespace

ProbeRelocation relocateProbe(const Scene& scene, glm::vec3 position, glm::vec3 spacing) {
  return relocateWith(RayTracer(scene), position, spacing);
}

std::vector<ProbeRelocation> relocateProbes(const Scene& scene, const VolumeGrid& grid,
                                            const std::vector<int>& which) {
  const RayTracer tracer(scene);
  std::vector<ProbeRelocation> out(which.size());
  parallelFor(0, static_cast<int>(which.size()), [&](int i) {
    out[static_cast<std::size_t>(i)] = relocateWith(
        tracer, shared::volumeGridPosition(grid, which[static_cast<std::size_t>(i)]), grid.spacing);
  });
  return out;
}

IrradianceVolume makeVolume(glm::vec3 lo, glm::vec3 hi, glm::ivec3 counts,
                            const VolumeOptions& options, const CaptureOptions& capture) {
  if (options.captureSize < 4 || options.captureSize > 256 || options.irradianceTexels < 2 ||
      options.irradianceTexels > 64 || options.distanceTexels < 2 || options.distanceTexels > 64 ||
      options.distanceRays < 1)
    throw Error("volume: map sizes out of range (capture 4..256, tiles 2..64)");
  IrradianceVolume v;
  v.grid = volumeGrid(lo, hi, counts, options);
  v.boundsLo = lo;
  v.boundsHi = hi;
  v.options = options;
  v.capture = capture;
  const glm::ivec2 e = atlasSize(v.grid, options.irradianceTexels);
  const glm::ivec2 d = atlasSize(v.grid, options.distanceTexels);
  v.irradiance = Image(e.x, e.y);
  v.distance = Image(d.x, d.y);
  v.probes.assign(static_cast<std::size_t>(volumeProbeCount(v.grid)), ProbeRelocation{});
  v.captured.assign(v.probes.size(), false);
  return v;
}

std::vector<glm::vec4> relocationRecords(const IrradianceVolume& volume) {
  std::vector<glm::vec4> records;
  records.reserve(volume.probes.size());
  for (const ProbeRelocation& p : volume.probes) records.emplace_back(p.offset, p.on ? 1.0f : 0.0f);
  return records;
}

double octahedralTexelSolidAngle(int x, int y, int size) {
  // Midpoint rule over 8 x 8 points of the texel; the Jacobian is smooth inside a texel except
  // across the diamond's edges, where it stays continuous.
  constexpr int kSub = 8;
  const double h = 2.0 / size;
  double sum = 0.0;
  for (int j = 0; j < kSub; ++j)
    for (int i = 0; i < kSub; ++i) {
      const double u = -1.0 + h * (x + (i + 0.5) / kSub);
      const double v = -1.0 + h * (y + (j + 0.5) / kSub);
      const double z = 1.0 - std::abs(u) - std::abs(v);
      // The point on the octahedron: (u, v, z) above, folded below; its length either way.
      const double qx = z >= 0.0 ? u : (1.0 - std::abs(v)) * (u >= 0.0 ? 1.0 : -1.0);
      const double qy = z >= 0.0 ? v : (1.0 - std::abs(u)) * (v >= 0.0 ? 1.0 : -1.0);
      const double len = std::sqrt(qx * qx + qy * qy + z * z);
      sum += 1.0 / (len * len * len);
    }
  return sum * h * h / (kSub * kSub);
}

namespace {

// The border of probe `probe`'s tile from its interior.
void fillTileBorder(Image& atlas, const VolumeGrid& g, int texels, int probe) {
  const glm::ivec2 o = tileOrigin(g, probe, texels);
  for (int y = 0; y < texels + 2; ++y)
    for (int x = 0; x < texels + 2; ++x) {
      const glm::ivec2 s = shared::volumeBorderSource({x, y}, texels);
      if (s != glm::ivec2(x, y)) atlas.at(o.x + x, o.y + y) = atlas.at(o.x + s.x, o.y + s.y);
    }
}

}  // namespace

void fillVolumeBorders(Image& atlas, const VolumeGrid& g, int texels) {
  const int count = volumeProbeCount(g);
  for (int probe = 0; probe < count; ++probe) fillTileBorder(atlas, g, texels, probe);
}

glm::vec3 sampleVolumeAtlas(const Image& atlas, glm::vec2 texel) {
  const glm::vec2 p = texel - 0.5f;
  const glm::vec2 f = glm::floor(p);
  const glm::vec2 t = p - f;
  const auto at = [&](int x, int y) {
    return atlas.at(std::clamp(x, 0, atlas.width - 1), std::clamp(y, 0, atlas.height - 1));
  };
  const int x0 = static_cast<int>(f.x), y0 = static_cast<int>(f.y);
  return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), t.x),
                  glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), t.x), t.y);
}

LobeSums cosineLobeSums(glm::vec3 normal, std::span<const glm::vec3> directions,
                        std::span<const float> weights, std::span<const glm::vec3> values,
                        double power) {
  LobeSums s;
  for (std::size_t i = 0; i < directions.size(); ++i) {
    const double c = glm::dot(normal, directions[i]);
    if (c <= 0.0) continue;
    const double w =
        (weights.empty() ? 1.0 : double{weights[i]}) * (power == 1.0 ? c : std::pow(c, power));
    s.weighted += w * glm::dvec3(values[i]);
    s.total += w;
  }
  return s;
}

void captureVolumeProbes(const Scene& scene, IrradianceVolume& volume,
                         const std::vector<int>& which, const BakeResult& bake,
                         const BakeOptions& bakeOptions,
                         const std::function<void(float)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  const VolumeGrid& g = volume.grid;
  const int n = volume.options.captureSize;
  const int cells = n * n;
  // The captured map's texels: direction and solid angle (the same for every probe).
  std::vector<glm::vec3> directions(static_cast<std::size_t>(cells));
  std::vector<float> solidAngles(static_cast<std::size_t>(cells));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * n + x;
      directions[i] =
          octahedralTexelDirection(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, n);
      solidAngles[i] = static_cast<float>(octahedralTexelSolidAngle(x, y, n));
    }
  // Distances beyond a cell's diagonal twice over are all "far": no lookup asks further.
  const float farthest = 2.0f * glm::length(g.spacing);
  const RayTracer tracer(scene);
  const int rays = volume.options.distanceRays;
  const int side = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(rays)))));
  RenderOptions o = captureRenderOptions(volume.capture, bakeOptions);
  // The distant environment seen through an opening is light the volume carries (it stands for
  // the environment inside its bounds); the lights seen directly are not (the split sum adds
  // them).
  o.backgroundEnvironment = true;
  std::size_t done = 0;
  for (const int probe : which) {
    const glm::vec3 position = shared::volumeGridPosition(g, probe) +
                               volume.probes[static_cast<std::size_t>(probe)].offset;
    // Radiance: the octahedral map path traced, each texel's samples spread over its area.
    const RayGenerator rayOf = [&](glm::vec2 pixel) {
      return Ray{position, shared::octahedralDecode(2.0f * pixel / static_cast<float>(n) - 1.0f)};
    };
    RenderOptions probeOptions = o;
    probeOptions.seed = volume.capture.seed + 7919u * static_cast<unsigned>(probe);
    const RenderResult radiance =
        renderRays(scene, n, n, rayOf, bake, bakeOptions, probeOptions, [&](float f) {
          if (progress) progress((static_cast<float>(done) + f) / static_cast<float>(which.size()));
        });
    // Distances: the mean and mean square over a side x side lattice of rays in each texel.
    std::vector<glm::vec3> moments(static_cast<std::size_t>(cells));  // mean, mean square, 0
    parallelFor(0, n, [&](int y) {
      for (int x = 0; x < n; ++x) {
        glm::vec2 m(0.0f);
        for (int j = 0; j < side; ++j)
          for (int i = 0; i < side; ++i) {
            const glm::vec3 d = octahedralTexelDirection(
                static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / static_cast<float>(side),
                static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / static_cast<float>(side),
                n);
            const RayTracer::Hit hit = tracer.intersect(Ray{position, d});
            const float t = hit.found ? std::min(hit.t, farthest) : farthest;
            m += glm::vec2(t, t * t);
          }
        moments[static_cast<std::size_t>(y) * n + x] =
            glm::vec3(m / static_cast<float>(side * side), 0.0f);
      }
    });
    // The stored tiles: irradiance / pi by quadrature over the captured texels, distances by
    // the cos^50 lobe.
    const int te = volume.options.irradianceTexels, td = volume.options.distanceTexels;
    const glm::ivec2 oe = tileOrigin(g, probe, te), od = tileOrigin(g, probe, td);
    parallelFor(0, te * te, [&](int t) {
      const int x = t % te, y = t / te;
      const glm::vec3 normal =
          octahedralTexelDirection(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, te);
      // The cosine-weighted mean of the radiance over the hemisphere (E / pi); its weights'
      // sum stands for their integral, pi, so that the texels' discretization cancels.
      const LobeSums e =
          cosineLobeSums(normal, directions, solidAngles, radiance.color.pixels, 1.0);
      volume.irradiance.at(oe.x + 1 + x, oe.y + 1 + y) = glm::vec3(e.weighted / e.total);
    });
    parallelFor(0, td * td, [&](int t) {
      const int x = t % td, y = t / td;
      const glm::vec3 normal =
          octahedralTexelDirection(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, td);
      const LobeSums m = cosineLobeSums(normal, directions, solidAngles, moments,
                                        shared::kVolumeDistanceSharpness);
      const glm::vec2 mean = m.total > 0.0 ? glm::vec2(m.weighted / m.total)
                                           : glm::vec2(farthest, farthest * farthest);
      volume.distance.at(od.x + 1 + x, od.y + 1 + y) = glm::vec3(mean, 0.0f);
    });
    // Only this probe's borders: capturing probe by probe stays linear in their number.
    fillTileBorder(volume.irradiance, g, te, probe);
    fillTileBorder(volume.distance, g, td, probe);
    volume.captured[static_cast<std::size_t>(probe)] = true;
    ++done;
  }
  volume.captureMilliseconds +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (progress) progress(1.0f);
}

glm::vec3 lookupVolume(const IrradianceVolume& volume, glm::vec3 p, glm::vec3 n, glm::vec3 v,
                       glm::vec3 diffuseDirection) {
  const VolumeGrid& g = volume.grid;
  glm::vec3 sum(0.0f);
  float total = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const int probe = shared::volumeCornerProbe(g, p, corner);
    const ProbeRelocation& r = volume.probes[static_cast<std::size_t>(probe)];
    const shared::VolumeCorner c =
        shared::volumeCorner(g, p, n, v, corner, glm::vec4(r.offset, r.on ? 1.0f : 0.0f));
    if (c.weight <= 0.0f) continue;
    const glm::vec3 moments = sampleVolumeAtlas(
        volume.distance, shared::volumeAtlasTexel(g, probe, c.direction, g.distanceTexels));
    const float w = shared::volumeCornerWeight(g, c, glm::vec2(moments));
    sum += w * sampleVolumeAtlas(
                   volume.irradiance,
                   shared::volumeAtlasTexel(g, probe, diffuseDirection, g.irradianceTexels));
    total += w;
  }
  return shared::volumeIrradiance(sum, total);
}

std::vector<std::string> volumeFileNames(const std::string& stem) {
  return {stem + ".json", atlasName("irradiance", stem), atlasName("distance", stem)};
}

void writeVolume(const IrradianceVolume& volume, const fs::path& dir, const std::string& stem) {
  const VolumeGrid& g = volume.grid;
  Json probes = Json::array();
  for (std::size_t i = 0; i < volume.probes.size(); ++i) {
    const ProbeRelocation& r = volume.probes[i];
    Json p = {{"linear", i},
              {"position", vec3Json(shared::volumeGridPosition(g, static_cast<int>(i)) + r.offset)},
              {"offset", vec3Json(r.offset)},
              {"on", r.on},
              {"captured", static_cast<bool>(volume.captured[i])}};
    if (!r.on) p["reason"] = r.reason;
    probes.push_back(p);
  }
  Json j;
  j["irradiance_volume"] = {
      {"bounds", {vec3Json(volume.boundsLo), vec3Json(volume.boundsHi)}},
      {"counts", {g.counts.x, g.counts.y, g.counts.z}},
      {"origin", vec3Json(g.origin)},
      {"spacing", vec3Json(g.spacing)},
      {"irradiance",
       {{"file", atlasName("irradiance", stem)},
        {"texels", g.irradianceTexels},
        {"content", "RGB: irradiance / pi (E / pi, linear Rec.709)"}}},
      {"distance",
       {{"file", atlasName("distance", stem)},
        {"texels", g.distanceTexels},
        {"content",
         "R: mean, G: mean squared distance to the first surface (scene "
         "units), cos^50 lobe"}}},
      {"capture_size", volume.options.captureSize},
      {"distance_rays", volume.options.distanceRays},
      {"normal_bias", g.normalBias},
      {"view_bias", g.viewBias},
      {"capture", Json::parse(captureRecordJson(volume.capture, volume.captureMilliseconds))},
      {"layout",
       "probe (i, j, k) at origin + spacing * (i, j, k) + its offset, linear index i + nx (j + "
       "ny k); its tile (texels + 2)^2 at column i + nx j, row k of each atlas; octahedral map "
       "of Cigolle et al. 2014 (+Z inside the diamond, u along +X, v along +Y, row 0 at v = "
       "-1) with a one-texel border repeating the interior across the map's edges"},
      {"lookup",
       "eight probes around the point, weighted by trilinear position, the smooth backface "
       "term and Chebyshev visibility from the distance moments, with the self-shadow bias "
       "(Majercik et al. 2019, JCGT 8(2))"},
      {"probes", probes}};
  const std::string text = j.dump(2) + "\n";
  std::vector<EncodedFile> files;
  files.push_back(
      {dir / atlasName("irradiance", stem), encodeKtx2(atlasTexture(volume.irradiance))});
  files.push_back({dir / atlasName("distance", stem), encodeKtx2(atlasTexture(volume.distance))});
  files.push_back({dir / (stem + ".json"), std::vector<std::uint8_t>(text.begin(), text.end())});
  writeFilesTogether(files);
}

IrradianceVolume loadVolume(const fs::path& path, const std::string& stem) {
  const fs::path manifest = fs::is_directory(path) ? path / (stem + ".json") : path;
  const fs::path dir = manifest.parent_path();
  if (!fs::is_regular_file(manifest))
    fail(path.string(), fmt::format("is not an irradiance volume (no {})", (stem + ".json")));
  const Json j = readJsonFile(manifest);
  IrradianceVolume v;
  try {
    const Json& r = j.at("irradiance_volume");
    const Json& counts = r.at("counts");
    const glm::ivec3 c(counts.at(0).get<int>(), counts.at(1).get<int>(), counts.at(2).get<int>());
    VolumeOptions o;
    o.irradianceTexels = r.at("irradiance").at("texels").get<int>();
    o.distanceTexels = r.at("distance").at("texels").get<int>();
    o.captureSize = r.value("capture_size", o.captureSize);
    o.distanceRays = r.value("distance_rays", o.distanceRays);
    o.normalBias = r.at("normal_bias").get<float>();
    o.viewBias = r.at("view_bias").get<float>();
    if (!std::isfinite(o.normalBias) || !std::isfinite(o.viewBias))
      throw std::runtime_error("a bias is not finite");
    const glm::vec3 lo = vec3From(r.at("bounds").at(0)), hi = vec3From(r.at("bounds").at(1));
    const CaptureOptions capture = parseCaptureRecord(r.at("capture").dump(), manifest.string());
    v = makeVolume(lo, hi, c, o, capture);
    v.captureMilliseconds = r.at("capture").value("milliseconds", 0.0);
    const Json& probes = r.at("probes");
    if (probes.size() != v.probes.size())
      throw std::runtime_error(
          fmt::format("lists {} probes; the grid has {}", probes.size(), v.probes.size()));
    const glm::vec3 limit = 0.45f * v.grid.spacing * 1.0001f;
    for (std::size_t i = 0; i < probes.size(); ++i) {
      ProbeRelocation& p = v.probes[i];
      p.offset = vec3From(probes[i].at("offset"));
      if (glm::any(glm::greaterThan(glm::abs(p.offset), limit)))
        throw std::runtime_error(fmt::format("probe {} moves beyond 0.45 of the spacing", i));
      p.on = probes[i].at("on").get<bool>();
      p.reason = probes[i].value("reason", "");
      v.captured[i] = probes[i].value("captured", true);
    }
    v.irradiance = readAtlas(dir / r.at("irradiance").at("file").get<std::string>(),
                             atlasSize(v.grid, o.irradianceTexels));
    v.distance = readAtlas(dir / r.at("distance").at("file").get<std::string>(),
                           atlasSize(v.grid, o.distanceTexels));
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail(manifest.string(), fmt::format("not an irradiance volume manifest: {}", e.what()));
  }
  v.path = manifest.string();
  return v;
}

ScreenAmbientOcclusionSettings occlusionUnderVolume(const ScreenAmbientOcclusionSettings& settings,
                                                    const IrradianceVolume* volume) {
  ScreenAmbientOcclusionSettings s = settings;
  if (volume && s.radius <= 0.0f) {
    const glm::vec3 spacing = volume->grid.spacing;
    s.radius = 0.5f * std::min(spacing.x, std::min(spacing.y, spacing.z));
  }
  return s;
}

void copyVolumeProbe(const IrradianceVolume& from, IrradianceVolume& to, int index) {
  const VolumeGrid& g = to.grid;
  if (from.grid.counts != g.counts || from.irradiance.width != to.irradiance.width ||
      from.distance.width != to.distance.width)
    throw Error("volume: the shards' grids differ");
  const auto copyTile = [&](const Image& src, Image& dst, int texels) {
    const glm::ivec2 o = tileOrigin(g, index, texels);
    for (int y = 0; y < texels + 2; ++y)
      for (int x = 0; x < texels + 2; ++x) dst.at(o.x + x, o.y + y) = src.at(o.x + x, o.y + y);
  };
  copyTile(from.irradiance, to.irradiance, g.irradianceTexels);
  copyTile(from.distance, to.distance, g.distanceTexels);
  to.probes[static_cast<std::size_t>(index)] = from.probes[static_cast<std::size_t>(index)];
  to.captured[static_cast<std::size_t>(index)] = from.captured[static_cast<std::size_t>(index)];
}

}  // namespace ibl
