#version 450
// The reference on the device (src/gpu/path_tracer.cpp): samples [first, first + count) of every
// pixel, added to its accumulation. The path is tracePath's (src/render/path_tracer.cpp) over
// the shared math: the numbers (ibl/shared/path_sampler.h), the lights' sampling
// (light_sampling.h), the material and its sampling (path_brdf.h, microfacet_walk.h), the
// triangles' BVH (bvh.h), glTF's alpha and textures (material.h); what stays here is reading the
// scene from its buffers, the environment's and the emitters' tables, and the loop.
layout(local_size_x = 8, local_size_y = 8) in;

#include "render/scene_buffers.glsl"

// The environment: the source cube's level 0 (what cube_buffer.glsl reads).
layout(std430, binding = 5) readonly buffer EnvironmentTexels {
  vec4 texels[];
};
layout(std430, binding = 6) readonly buffer EnvironmentLevels {
  uvec2 levels[];
};
// The environment's row CDF (6n), its rows' column CDFs (6n^2), the albedo tables (2 x 33^2),
// the Charlie table (ibl/shared/charlie_table.h), then each IES light's intensity table
// (kIesRows x kIesColumns).
layout(std430, binding = 7) readonly buffer Tables {
  float tables[];
};
// Per pixel: (radiance sum, covered samples), (luminance sum, luminance^2 sum, 0, 0).
layout(std430, binding = 8) buffer Accumulation {
  vec4 accumulation[];
};

const int kFlagVisibility = 1;
const int kFlagEnvironmentLight = 2;
const int kFlagBackgroundEnvironment = 4;
const int kFlagCameraSeesEmitters = 8;
const int kFlagCameraSeesSpecular = 16;
const int kFlagCaptureMetalsAsDiffuse = 32;
const int kFlagPixelCenter = 64;
const int kFlagTransmits = 128;  // some material transmits (hasTransmission)
const float kInfinity = 1e30;

bool flag(int f) {
  return (params.path.z & f) != 0;
}

int environmentSize() {
  return int(params.counts.w);
}
// Where the albedo tables start in `tables`: after the environment's CDFs.
int albedoTablesStart() {
  int n = environmentSize();
  return 6 * n + 6 * n * n;
}
float albedoTableNode(int table, int index) {
  return tables[albedoTablesStart() + table * 33 * 33 + index];
}

#include "ibl/shared/cube.h"
#include "ibl/shared/light_sampling.h"
#include "ibl/shared/path_brdf.h"
#include "env/cube_buffer.glsl"

// The sheen's exact Lambda reads its table after the albedo tables (brdf.h declares this).
int charlieTableStart() {
  return albedoTablesStart() + 2 * 33 * 33;
}
float charlieTableEntry(int k) {
  return tables[charlieTableStart() + k];
}

// --- Lights ---

// Light i's record (ibl/shared/light_record.h; uploadSceneBuffers in src/gpu/scene_buffers.cpp).
LightRecord lightRecordAt(uint i) {
  uint b = params.offsets.w + uint(kLightRecordVec4s) * i;
  return LightRecord(sceneData[b], sceneData[b + 1u], sceneData[b + 2u], sceneData[b + 3u],
                     sceneData[b + 4u]);
}
ShadingLight lightAt(uint i) {
  return unpackLight(lightRecordAt(i));
}

// An IES light's intensity toward w (leaving the light), candela x its scale, bilinear in its
// table of 0.5-degree steps (appendIesTable in src/gpu/path_tracer.cpp).
const int kIesRows = 361;
const int kIesColumns = 721;
float iesIntensity(ShadingLight l, float table, vec3 w) {
  vec2 angles = iesAngles(iesNadir(l), w);  // vertical, horizontal
  vec2 p = vec2(angles.y, angles.x) / 0.5;
  ivec2 i = min(ivec2(p), ivec2(kIesColumns - 2, kIesRows - 2));
  vec2 f = p - vec2(i);
  int base = charlieTableStart() + kCharlieTableRoughnesses * kCharlieTableAngles +
             int(table) * kIesRows * kIesColumns;
  int a = base + i.y * kIesColumns + i.x;
  return mix(mix(tables[a], tables[a + 1], f.x),
             mix(tables[a + kIesColumns], tables[a + kIesColumns + 1], f.x), f.y);
}

// The nearest light the ray meets (nearestLight in src/render/path_tracer.cpp): its index or -1.
int nearestLight(vec3 p, vec3 w, out float distance, out vec3 radiance) {
  int best = -1;
  distance = kInfinity;
  radiance = vec3(0.0);
  for (uint i = 0u; i < params.counts.x; ++i) {
    ShadingLight l = lightAt(i);
    float t = emitterDistance(l, p, w);
    if (t >= 0.0 && (best < 0 || t < distance)) {
      best = int(i);
      distance = t;
      radiance = emitterRadiance(l, w);
    }
  }
  return best;
}

// --- The environment (EnvironmentSampler in src/render/path_tracer.hpp) ---

int rowCdfStart() {
  return 0;
}
int columnCdfStart() {
  return 6 * environmentSize();
}
float cdfInterval(int start, int i) {
  return tables[start + i] - (i > 0 ? tables[start + i - 1] : 0.0);
}
// The entry of a CDF of `count` entries from `start` whose interval holds x, and where in it.
int invertCdf(int start, int count, float x, out float within) {
  int lo = 0, hi = count - 1;
  while (lo < hi) {  // the first entry > x (upper_bound)
    int mid = (lo + hi) / 2;
    if (tables[start + mid] > x)
      hi = mid;
    else
      lo = mid + 1;
  }
  float below = lo > 0 ? tables[start + lo - 1] : 0.0;
  within = clamp((x - below) / max(tables[start + lo] - below, 1e-30), 0.0, 1.0);
  return lo;
}
ivec3 environmentTexelOf(vec3 dir) {
  int n = environmentSize();
  FacePoint p = directionToFace(dir);
  return ivec3(p.face, clamp(int(p.s * float(n)), 0, n - 1), clamp(int(p.t * float(n)), 0, n - 1));
}
vec3 environmentRadiance(vec3 dir) {
  ivec3 t = environmentTexelOf(dir);
  return texel(0, t.x, t.y, t.z);
}
float environmentPdf(vec3 dir) {
  int n = environmentSize();
  ivec3 t = environmentTexelOf(dir);
  int row = t.x * n + t.z;
  FacePoint fp = directionToFace(dir);
  float sc = 2.0 * fp.s - 1.0, tc = 2.0 * fp.t - 1.0;
  float q = 1.0 + sc * sc + tc * tc;
  return cdfInterval(rowCdfStart(), row) * cdfInterval(columnCdfStart() + row * n, t.y) *
         (q * sqrt(q)) / (4.0 / float(n * n));
}
vec3 sampleEnvironment(vec2 xi) {
  int n = environmentSize();
  float v, u;
  int row = invertCdf(rowCdfStart(), 6 * n, xi.x, v);
  int x = invertCdf(columnCdfStart() + row * n, n, xi.y, u);
  int face = row / n, y = row % n;
  float inv = 2.0 / float(n);
  return normalize(faceToDirection(face, (float(x) + u) * inv - 1.0, (float(y) + v) * inv - 1.0));
}

// --- Emissive triangles (EmissiveTriangles in src/render/emissive_triangles.cpp) ---

vec4 emitterAt(uint i) {
  return sceneData[params.offsets2.y + i];
}
float emitterProbability(uint i) {
  return emitterAt(i).w - (i > 0u ? emitterAt(i - 1u).w : 0.0);
}

struct EmitterSample {
  vec3 direction;
  float distance;
  vec3 radiance;
  float pdf;
};

// A point on an emissive triangle seen from p, xi uniform in [0, 1)^3 (x picks the triangle by
// power, y and z a point uniform over it: pbrt-v4, 6.5.4's square-root parameterization).
EmitterSample sampleEmitters(vec3 p, vec3 xi) {
  EmitterSample s = EmitterSample(vec3(0.0, 0.0, 1.0), 0.0, vec3(0.0), 0.0);
  uint count = params.counts.z;
  uint lo = 0u, hi = count - 1u;
  while (lo < hi) {  // the first entry >= x (lower_bound)
    uint mid = (lo + hi) / 2u;
    if (emitterAt(mid).w >= xi.x)
      hi = mid;
    else
      lo = mid + 1u;
  }
  vec4 e = emitterAt(lo);
  uint mesh = floatBitsToUint(e.x), primitive = floatBitsToUint(e.y);
  MeshRecord m = meshAt(mesh);
  uvec3 tri = triangleVertices(m, primitive);
  float su = sqrt(xi.y);
  float b1 = su * (1.0 - xi.z), b2 = su * xi.z;
  vec3 a = vertexAt(tri.x, 0).xyz, e1 = vertexAt(tri.y, 0).xyz - a, e2 = vertexAt(tri.z, 0).xyz - a;
  vec3 d = a + b1 * e1 + b2 * e2 - p;
  float dist2 = dot(d, d);
  if (!(dist2 > 0.0)) return s;
  float dist = sqrt(dist2);
  vec3 w = d / dist;
  float cosLight = abs(dot(normalize(cross(e1, e2)), w));
  if (!(cosLight > 1e-6)) return s;
  // Area density 1 / A to solid angle: times d^2 / |cos theta_light|.
  s.pdf = emitterProbability(lo) / e.z * dist2 / cosLight;
  s.direction = w;
  s.distance = dist;
  s.radiance = surfaceAt(SceneHit(true, dist, false, mesh, primitive, b1, b2), p, w).emissive;
  return s;
}

// The density with which sampleEmitters picks the point at distance t along w on a triangle.
float emitterPdf(vec3 w, float t, uint mesh, uint primitive) {
  uint start = words[params.offsets2.w + mesh];
  if (start == 0xffffffffu) return 0.0;
  uint entry = words[params.offsets2.w + start + primitive];
  if (entry == 0xffffffffu) return 0.0;
  MeshRecord m = meshAt(mesh);
  uvec3 tri = triangleVertices(m, primitive);
  vec3 a = vertexAt(tri.x, 0).xyz;
  vec3 ng = normalize(cross(vertexAt(tri.y, 0).xyz - a, vertexAt(tri.z, 0).xyz - a));
  float cosLight = abs(dot(ng, w));
  if (!(cosLight > 1e-6)) return 0.0;
  return emitterProbability(entry) / emitterAt(entry).z * t * t / cosLight;
}

// --- The path (tracePath in src/render/path_tracer.cpp) ---

PathShading pathShading() {
  PathShading o;
  o.diffuseModel = params.shading.x;
  o.multipleScattering = params.shading.y;
  o.specularMicroOcclusion = params.shading.z != 0;
  o.sheenVisibility = params.shading.w;
  return o;
}

// The relative index below the surface (transmissionEta in src/render/path_tracer.cpp).
float transmissionEta(Surface p) {
  return p.volume ? volumeRelativeIndex(p.ior, p.frontFace) : 0.0;
}

// tracePath's rules for a surface that transmits (src/render/path_tracer.cpp): lit and left on
// both sides (local l.z < 0 too); the side of its own plane that world direction w goes to is
// where it leaves from, and whether it goes on inside the volume (a thin wall keeps the medium).
bool leavesToward(bool twoSided, vec3 l) {
  return l.z > 0.0 || (twoSided && l.z < 0.0);
}
vec3 originToward(Surface p, bool twoSided, vec3 origin, vec3 position, vec3 offset, vec3 w) {
  if (!twoSided) return origin;
  return position + p.faceNormal * (dot(w, p.faceNormal) < 0.0 ? -1.0 : 1.0) * length(offset);
}
vec3 mediumToward(Surface p, bool twoSided, vec3 medium, vec3 w) {
  if (!twoSided || !p.volume) return medium;
  return dot(w, p.faceNormal) < 0.0 ? p.attenuation : vec3(0.0);
}

// The share of light that crosses `distance` of the medium sigma (1 without one).
vec3 crossing(vec3 sigma, float distance) {
  return sigma == vec3(0.0) ? vec3(1.0) : volumeTransmittance(sigma, distance);
}

// The material at p (a capture's metals as diffuse) as the path shades it, seen from local
// direction v in the frame toLocal (vertexBrdf in src/render/path_tracer.cpp).
PathBrdf vertexBrdf(inout Surface p, mat3 toLocal, vec3 v, bool seenByProbe) {
  int lobes = seenByProbe ? kLobesCapture : params.path.y;
  if (seenByProbe && flag(kFlagCaptureMetalsAsDiffuse)) p = metalAsDiffuse(p);
  PathShading shading = pathShading();
  PathBrdf brdf = pathBrdfOf(p.baseColor, p.metallic, p.roughness,
                             surfaceReflectance(p, shading.specularMicroOcclusion), p.sheenColor,
                             p.sheenRoughness, v, lobes, shading);
  if (p.clearcoat > 0.0)
    brdf = withClearcoat(brdf, p.clearcoat, p.clearcoatRoughness, toLocal * p.clearcoatNormal, v);
  if (p.anisotropy > 0.0)
    brdf = withAnisotropy(brdf, p.anisotropy, toLocal * p.anisotropyTangent, v, shading);
  if (p.transmission > 0.0)
    brdf = withTransmission(brdf, p.transmission, p.baseColor, p.metallic, transmissionEta(p), v);
  return brdf;
}

// What arrives at origin of the light that leaves origin + distance w toward it: nothing behind a
// surface the path would scatter on, through those it crosses straight their transmittance
// (shadowTransmittance in src/render/path_tracer.cpp).
vec3 shadowTransmittance(vec3 origin, vec3 w, float distance, bool seenByProbe) {
  if (!flag(kFlagVisibility)) return vec3(1.0);
  float reach = distance < kInfinity * 0.5 ? distance * (1.0 - 1e-4) : kInfinity;
  if (!flag(kFlagTransmits)) return vec3(occluded(origin, w, reach) ? 0.0 : 1.0);
  vec3 passed = vec3(1.0);
  for (int surfaces = 0; surfaces < 256 && reach > 0.0; ++surfaces) {
    SceneHit hit = intersectScene(origin, w, reach, false);
    if (!hit.found) return passed;
    if (!materialTransmits(hit)) return vec3(0.0);
    Surface q = surfaceAt(hit, origin, w);
    mat3 toLocal = transpose(tangentFrame(q.normal));
    vec3 v = toLocal * -w;
    PathBrdf b = vertexBrdf(q, toLocal, v, seenByProbe);
    if (!pathCrossesStraight(b)) return vec3(0.0);
    passed *= pathStraightTransmittance(b, v);
    // On from just past it, as crossTransmissive (src/render/ray_tracer.hpp) steps.
    float step = hit.t + 1e-4 * max(1.0, length(origin + hit.t * w));
    origin += step * w;
    reach -= step;
  }
  return reach > 0.0 ? vec3(0.0) : passed;  // more surfaces than the bound: taken as opaque
}

// The most surfaces one path crosses straight (kMaxCrossings in src/render/path_tracer.cpp).
const int kMaxCrossings = 256;

vec3 tracePath(Surface p, vec3 position, vec3 view, inout PathSampler numbers) {
  vec3 sum = vec3(0.0), throughput = vec3(1.0);
  vec3 medium = vec3(0.0);  // the volume the path travels in (KHR_materials_volume)
  // A probe capture keeps the diffuse of the surfaces it sees, and of those seen through them.
  bool seenByProbe = !flag(kFlagCameraSeesSpecular);
  // Where the path last scattered (Scattering in src/render/path_tracer.cpp): its sample's
  // density (0: the camera's ray), the points it left from, and how far it has gone since.
  float lastPdf = 0.0, travelled = 0.0;
  vec3 lastOrigin = position, lastPosition = position;
  // Bounces count scatterings; past the last one the path goes on through straight surfaces only.
  int bounce = 0, crossings = 0;
  bool pastLastBounce = false;
  sum += p.emissive;
  for (;;) {
    mat3 frame = tangentFrame(p.normal);
    mat3 toLocal = transpose(frame);
    vec3 v = toLocal * view;
    PathBrdf brdf = vertexBrdf(p, toLocal, v, seenByProbe);
    vec3 offset = p.normal * 1e-4 * max(1.0, length(position));
    // A smooth thin wall is crossed (its transmission's share) or met (its other lobes).
    bool straight = false;
    // A surface that transmits (met or crossed) is left by the side of its own plane.
    bool sidedByPlane = pathTransmissionLobe(brdf);
    if (pathCrossesStraight(brdf)) {
      if (++crossings > kMaxCrossings) break;
      float chance = pastLastBounce ? 1.0 : pathTransmissionProbability(brdf, v);
      straight = pastLastBounce || pathUniform(numbers) < chance;
      if (straight)
        throughput *= pathStraightTransmittance(brdf, v) / chance;
      else
        throughput /= 1.0 - chance;
      brdf = withoutTransmission(brdf);
    }
    if (pastLastBounce && !straight) break;
    vec3 origin = position + offset;
    bool twoSided = pathTransmissionLobe(brdf);
    vec3 w;
    if (straight) {
      origin = position + p.faceNormal * (dot(view, p.faceNormal) > 0.0 ? -1.0 : 1.0) * length(offset);
      w = -view;
    } else {
      // Next-event estimation: one sample of each light, one of the emitters and one of the
      // environment, in this order (their draws' dimensions), each weighed against the BRDF's
      // sampling and passed through one shadow ray (one call of each function: a shader's code
      // is inlined, and lavapipe compiles every copy).
      for (uint k = 0u; k < params.counts.x + 2u; ++k) {
        vec3 direction = vec3(0.0, 0.0, 1.0), radiance = vec3(0.0);
        float distance = kInfinity, pdf = 0.0;
        bool delta = false, weighed = true;
        if (k < params.counts.x) {
          ShadingLight light = lightAt(k);
          vec2 xi = pathUniform2(numbers);
          delta = light.type == kLightPoint || light.type == kLightSpot;
          if (delta) {
            vec3 d = light.position - origin;
            distance = length(d);
            direction = d / distance;
            radiance = light.color * punctualLightIrradiance(light, origin);
            float ies = lightRecordProfile(lightRecordAt(k));
            if (ies >= 0.0) radiance *= iesIntensity(light, ies, -direction);
          } else {
            AreaLightSample ls = sampleAreaLight(light, origin, xi);
            direction = ls.direction;
            distance = ls.distance;
            radiance = ls.radiance * lightRangeWindow(light, origin);
            pdf = ls.pdf;
          }
        } else if (k == params.counts.x) {
          if (params.counts.z == 0u) continue;
          float pick = pathUniform(numbers);
          vec2 point = pathUniform2(numbers);
          EmitterSample es = sampleEmitters(origin, vec3(pick, point));
          float ld;
          vec3 lr;
          // An analytic light in front hides it, as it stops the BRDF's samples; without
          // visibility those are not traced, and this sample takes all the weight.
          if (nearestLight(origin, es.direction, ld, lr) >= 0 && ld < es.distance) continue;
          direction = es.direction;
          distance = es.distance;
          radiance = es.radiance;
          pdf = es.pdf;
          weighed = flag(kFlagVisibility);
        } else {
          if (!flag(kFlagEnvironmentLight)) continue;
          direction = sampleEnvironment(pathUniform2(numbers));
          float ld;
          vec3 lr;
          if (nearestLight(origin, direction, ld, lr) >= 0) continue;
          radiance = environmentRadiance(direction);
          pdf = environmentPdf(direction);
        }
        vec3 l = toLocal * direction;
        if (!(delta || pdf > 0.0) || radiance == vec3(0.0) || !leavesToward(twoSided, l)) continue;
        float weight = delta     ? 1.0
                       : weighed ? powerHeuristic(pdf, pathBrdfPdf(brdf, v, l)) / pdf
                                 : 1.0 / pdf;
        // The BRDF evaluated only where the shadow ray lets something through.
        vec3 passed =
            shadowTransmittance(originToward(p, sidedByPlane, origin, position, offset, direction),
                                direction, distance, seenByProbe && l.z < 0.0) *
            crossing(mediumToward(p, twoSided, medium, direction), distance);
        if (passed == vec3(0.0)) continue;
        sum += throughput * evaluatePathBrdf(brdf, v, l, numbers, true) * radiance * weight * passed;
      }
      // The BRDF's sample: it ends on a light or the environment, or goes on from what it meets.
      PathBrdfSample bs = samplePathBrdf(brdf, v, numbers);
      vec3 l = bs.direction;
      float pb = pathBrdfPdf(brdf, v, l);
      if (!(pb > 0.0) || bs.weight == vec3(0.0)) break;
      throughput *= bs.weight;
      w = frame * l;
      medium = mediumToward(p, twoSided, medium, w);
      seenByProbe = seenByProbe && twoSided && l.z < 0.0;
      origin = originToward(p, sidedByPlane, origin, position, offset, w);
      lastPdf = pb;
      lastOrigin = origin;
      lastPosition = position;
      travelled = 0.0;
    }
    // The camera's ray through a window is seen as the camera sees (tracePath's fromCamera).
    bool fromCamera = lastPdf == 0.0;
    SceneHit hit = flag(kFlagVisibility) || fromCamera
                       ? intersectScene(origin, w, kInfinity, false)
                       : SceneHit(false, kInfinity, false, 0u, 0u, 0.0, 0.0);
    float ld;
    vec3 lr;
    int seen = !fromCamera || flag(kFlagCameraSeesEmitters) ? nearestLight(origin, w, ld, lr) : -1;
    if (seen >= 0 && (!hit.found || ld < hit.t)) {
      ShadingLight light = lightAt(uint(seen));
      float weight = fromCamera ? 1.0 : powerHeuristic(lastPdf, areaLightPdf(light, lastOrigin, w));
      sum += throughput * lr * (fromCamera ? 1.0 : lightRangeWindow(light, lastPosition)) * weight *
             crossing(medium, ld);
      break;
    }
    if (!hit.found) {
      if (flag(kFlagEnvironmentLight))
        sum += throughput * environmentRadiance(w) *
               (lastPdf > 0.0 ? powerHeuristic(lastPdf, environmentPdf(w)) : 1.0) *
               crossing(medium, kInfinity);
      break;
    }
    throughput *= crossing(medium, hit.t);
    travelled += hit.t;
    // The surface met (read once: a shader inlines every call), and its emission weighed
    // against the sampling of the emitters.
    Surface next = surfaceAt(hit, origin, w);
    if (next.emissive != vec3(0.0)) {
      float pe = hit.sphere || params.counts.z == 0u
                     ? 0.0
                     : emitterPdf(w, travelled, hit.mesh, hit.primitive);
      sum += throughput * next.emissive * (lastPdf > 0.0 ? powerHeuristic(lastPdf, pe) : 1.0);
    }
    if (!straight) {
      if (bounce >= params.path.x) {
        // Only a surface that may be crossed straight is worth going on to.
        if (!materialTransmits(hit)) break;
        pastLastBounce = true;
      } else if (bounce >= 1) {
        // Russian roulette after two bounces: go on with the probability of the throughput.
        float q = min(max(throughput.x, max(throughput.y, throughput.z)), 0.95);
        if (!(pathUniform(numbers) < q)) break;
        throughput /= q;
      }
      ++bounce;
    }
    p = next;
    position = origin + hit.t * w;
    view = -w;
  }
  return sum;
}

// --- The pixel (renderRays in src/render/renderer.cpp) ---

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.image.x || pixel.y >= params.image.y) return;
  uint stream = pixel.y * params.image.x + pixel.x;
  uint key = pathSamplerKey(uint(params.path.w), 0u, stream, 0u);
  vec3 sum = vec3(0.0);
  float covered = 0.0, lumSum = 0.0, lumSquares = 0.0;
  for (uint s = 0u; s < params.image.w; ++s) {
    PathSampler numbers = pathSamplerAt(key, params.image.z + s);
    vec2 j = flag(kFlagPixelCenter) ? vec2(0.5) : pathUniform2(numbers);
    float x = 2.0 * (float(pixel.x) + j.x) / float(params.image.x) - 1.0;
    float y = 1.0 - 2.0 * (float(pixel.y) + j.y) / float(params.image.y);
    vec3 origin, dir;
    if (params.cameraPosition.w != 0.0) {
      origin = params.cameraPosition.xyz;
      dir = normalize(params.cameraForward.xyz + x * params.cameraRight.xyz + y * params.cameraUp.xyz);
    } else {
      origin = params.cameraPosition.xyz + x * params.cameraRight.xyz + y * params.cameraUp.xyz;
      dir = params.cameraForward.xyz;
    }
    SceneHit hit = intersectScene(origin, dir, kInfinity, false);
    float ld = kInfinity;
    vec3 lr = vec3(0.0);
    int seen = flag(kFlagCameraSeesEmitters) ? nearestLight(origin, dir, ld, lr) : -1;
    vec3 c;
    if (seen >= 0 && (!hit.found || ld < hit.t)) {
      if (ld < kSunDistance) covered += 1.0;  // an emitter is a surface; the sun is not
      c = lr;
    } else if (!hit.found) {
      c = flag(kFlagBackgroundEnvironment) ? sampleBilinear(0, dir) : params.background.rgb;
    } else {
      covered += 1.0;
      Surface p = surfaceAt(hit, origin, dir);
      c = tracePath(p, p.position, -dir, numbers);
    }
    sum += c;
    float l = luminance(c);
    lumSum += l;
    lumSquares += l * l;
  }
  accumulation[2u * stream] += vec4(sum, covered);
  accumulation[2u * stream + 1u] += vec4(lumSum, lumSquares, 0.0, 0.0);
}
