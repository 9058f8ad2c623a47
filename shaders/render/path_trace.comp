#version 450
// The reference on the device (src/gpu/path_tracer.cpp): samples [first, first + count) of every
// pixel, added to its accumulation. The path is tracePath's (src/render/path_tracer.cpp) over
// the shared math: the numbers (ibl/shared/path_sampler.h), the lights' sampling
// (light_sampling.h), the material and its sampling (path_brdf.h, microfacet_walk.h), the
// triangles' BVH (bvh.h), glTF's alpha and textures (material.h); what stays here is reading the
// scene from its buffers, the environment's and the emitters' tables, and the loop.
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer Parameters {
  vec4 cameraPosition;  // w: 1 perspective, 0 orthographic
  vec4 cameraForward;
  vec4 cameraRight;  // scaled to the image's half width (perspective: at distance 1)
  vec4 cameraUp;     // scaled to its half height
  vec4 background;   // rgb: the background without the environment
  uvec4 image;       // width, height, first sample index, samples
  uvec4 counts;      // lights, spheres, emitters, the environment's cube size
  uvec4 offsets;     // in sceneData: vertices, materials, textures, lights
  uvec4 offsets2;    // in sceneData: spheres, emitters; in words: texels, emitter entries
  ivec4 shading;     // PathShading: diffuse, multiple scattering, micro-occlusion, sheen
  ivec4 path;        // bounces, lobes, flags (kFlag...), seed
} params;
// The BVH (src/gpu/bvh.hpp): nodes, then triangles.
layout(std430, binding = 1) readonly buffer Nodes {
  vec4 nodes[];
};
layout(std430, binding = 2) readonly buffer Triangles {
  vec4 bvhTriangles[];
};
// Meshes (one vec4 of uint bits each: first vertex, first index, material, flags), vertices
// (three each), materials (six), textures (one), lights (five), spheres (two), emitters (one):
// uploadScene in src/gpu/path_tracer.cpp.
layout(std430, binding = 3) readonly buffer SceneData {
  vec4 sceneData[];
};
// The meshes' indices, then the textures' texels (RGBA8), then per emissive mesh and primitive
// its emitter's entry (or ~0).
layout(std430, binding = 4) readonly buffer Words {
  uint words[];
};
// The environment: the source cube's level 0 (what cube_buffer.glsl reads).
layout(std430, binding = 5) readonly buffer EnvironmentTexels {
  vec4 texels[];
};
layout(std430, binding = 6) readonly buffer EnvironmentLevels {
  uvec2 levels[];
};
// The environment's row CDF (6n), its rows' column CDFs (6n^2), the albedo tables (2 x 33^2),
// then each IES light's intensity table (kIesRows x kIesColumns).
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
const float kInfinity = 1e30;

bool flag(int f) {
  return (params.path.z & f) != 0;
}

int environmentSize() {
  return int(params.counts.w);
}
float albedoTableNode(int table, int index) {
  int n = environmentSize();
  return tables[6 * n + 6 * n * n + table * 33 * 33 + index];
}

#include "ibl/shared/lang.h"
#include "ibl/shared/cube.h"
#include "ibl/shared/light_record.h"
#include "ibl/shared/light_sampling.h"
#include "ibl/shared/material.h"
#include "ibl/shared/path_brdf.h"
#include "ibl/shared/bvh.h"
#include "env/cube_buffer.glsl"

uint bitsAt(vec4 v, int c) {
  return floatBitsToUint(v[c]);
}

// --- Textures (Texture::sample in src/render/scene.cpp) ---

vec4 texelAt(uvec4 t, int x, int y, bool srgb) {
  int w = int(t.y), h = int(t.z);
  int wx = wrapTexel(x, w, int(t.w & 3u)), wy = wrapTexel(y, h, int((t.w >> 2u) & 3u));
  uint packed = words[params.offsets2.z + t.x + uint(wy * w + wx)];
  vec4 c = vec4(float(packed & 255u), float((packed >> 8u) & 255u), float((packed >> 16u) & 255u),
                float(packed >> 24u)) / 255.0;
  if (srgb) c.rgb = srgbToLinear(c.rgb);
  return c;
}

vec4 sampleTexture(int index, vec2 uv, bool srgb) {
  vec4 r = sceneData[params.offsets.z + uint(index)];
  uvec4 t = uvec4(bitsAt(r, 0), bitsAt(r, 1), bitsAt(r, 2), bitsAt(r, 3));
  float fx = uv.x * float(t.y), fy = uv.y * float(t.z);
  if ((t.w & 16u) != 0u) return texelAt(t, int(floor(fx)), int(floor(fy)), srgb);
  float flx = floor(fx - 0.5), fly = floor(fy - 0.5);
  float wx = fx - 0.5 - flx, wy = fy - 0.5 - fly;
  int x0 = int(flx), y0 = int(fly);
  return (texelAt(t, x0, y0, srgb) * (1.0 - wx) + texelAt(t, x0 + 1, y0, srgb) * wx) * (1.0 - wy) +
         (texelAt(t, x0, y0 + 1, srgb) * (1.0 - wx) + texelAt(t, x0 + 1, y0 + 1, srgb) * wx) * wy;
}

// --- Meshes and materials ---

struct MeshRecord {
  uint firstVertex, firstIndex, material, flags;  // flags: 1 tangents, 2 uv0, 4 uv1, 8 emitters
};
MeshRecord meshAt(uint mesh) {
  vec4 r = sceneData[mesh];
  return MeshRecord(bitsAt(r, 0), bitsAt(r, 1), bitsAt(r, 2), bitsAt(r, 3));
}
uvec3 triangleVertices(MeshRecord m, uint primitive) {
  uint i = m.firstIndex + 3u * primitive;
  return m.firstVertex + uvec3(words[i], words[i + 1u], words[i + 2u]);
}
// A vertex: (position, uv0.x), (normal, uv0.y), tangent, (uv1, 0, 0).
vec4 vertexAt(uint v, int k) {
  return sceneData[params.offsets.x + 4u * v + uint(k)];
}
vec4 materialAt(uint material, int k) {
  return sceneData[params.offsets.y + 6u * material + uint(k)];
}
// A texture slot: (texture index, texCoord) or texture -1.
ivec2 slotOf(float encoded) {
  int e = int(encoded);
  return e < 0 ? ivec2(-1, 0) : ivec2(e >> 1, e & 1);
}
// The UV of a slot at barycentrics (w0, u, v), or false when the mesh lacks its set.
bool slotUv(MeshRecord m, uvec3 tri, ivec2 slot, vec3 w, out vec2 uv) {
  uv = vec2(0.0);
  if (slot.x < 0) return false;
  if (slot.y == 0 && (m.flags & 2u) == 0u) return false;
  if (slot.y == 1 && (m.flags & 4u) == 0u) return false;
  for (int k = 0; k < 3; ++k)
    uv += w[k] * (slot.y == 0 ? vec2(vertexAt(tri[k], 0).w, vertexAt(tri[k], 1).w)
                              : vertexAt(tri[k], 3).xy);
  return true;
}

bool bvhCovers(int triangle, float u, float v, vec3 origin, vec3 dir) {
  uint mesh = floatBitsToUint(bvhTriangles[3 * triangle].w);
  uint primitive = floatBitsToUint(bvhTriangles[3 * triangle + 1].w);
  MeshRecord m = meshAt(mesh);
  vec4 m3 = materialAt(m.material, 3);
  int mode = int(m3.z);
  if (mode == 0) return true;
  float alpha = materialAt(m.material, 0).w;
  ivec2 slot = slotOf(materialAt(m.material, 4).x);
  vec2 uv;
  if (slotUv(m, triangleVertices(m, primitive), slot, vec3(1.0 - u - v, u, v), uv))
    alpha *= sampleTexture(slot.x, uv, false).a;
  return alphaCovers(mode, alpha, m3.w, rayBlendThreshold(origin, dir, primitive));
}
vec4 bvhNodeAt(int i) {
  return nodes[i];
}
vec4 bvhTriangleAt(int i) {
  return bvhTriangles[i];
}

// --- The scene's surfaces (RayTracer and surfaceAt in src/render/ray_tracer.cpp) ---

struct SceneHit {
  bool found;
  float t;
  bool sphere;
  uint mesh;       // or the sphere
  uint primitive;
  float u, v;
};

SceneHit intersectScene(vec3 origin, vec3 dir, float tMax, bool anyHit) {
  SceneHit h = SceneHit(false, tMax, false, 0u, 0u, 0.0, 0.0);
  BvhHit b = bvhIntersect(origin, dir, tMax, anyHit);
  if (b.found) {
    h = SceneHit(true, b.t, false, floatBitsToUint(bvhTriangles[3 * b.triangle].w),
                 floatBitsToUint(bvhTriangles[3 * b.triangle + 1].w), b.u, b.v);
    if (anyHit) return h;
  }
  for (uint s = 0u; s < params.counts.y; ++s) {
    vec4 sphere = sceneData[params.offsets2.x + 2u * s];
    float t = raySphereDistance(origin, dir, sphere.xyz, sphere.w);
    if (t > 0.0 && t < h.t) {
      h = SceneHit(true, t, true, s, 0u, 0.0, 0.0);
      if (anyHit) return h;
    }
  }
  return h;
}

bool occluded(vec3 origin, vec3 dir, float maxDistance) {
  return intersectScene(origin, dir, maxDistance, true).found;
}

struct Surface {
  vec3 position, normal;
  vec3 baseColor;
  float metallic, roughness;
  vec3 emissive;
  vec3 sheenColor;
  float sheenRoughness;
};

Surface surfaceAt(SceneHit hit, vec3 origin, vec3 dir) {
  Surface p;
  p.position = origin + hit.t * dir;
  vec3 n;
  uint material;
  if (hit.sphere) {
    vec4 sphere = sceneData[params.offsets2.x + 2u * hit.mesh];
    n = normalize(p.position - sphere.xyz);
    material = floatBitsToUint(sceneData[params.offsets2.x + 2u * hit.mesh + 1u].x);
  } else {
    MeshRecord m = meshAt(hit.mesh);
    material = m.material;
    uvec3 tri = triangleVertices(m, hit.primitive);
    vec3 w = vec3(1.0 - hit.u - hit.v, hit.u, hit.v);
    n = normalize(vertexAt(tri.x, 1).xyz * w.x + vertexAt(tri.y, 1).xyz * w.y +
                  vertexAt(tri.z, 1).xyz * w.z);
    vec4 m0 = materialAt(material, 0), m1 = materialAt(material, 1), m2 = materialAt(material, 2),
         m3 = materialAt(material, 3), m4 = materialAt(material, 4), m5 = materialAt(material, 5);
    vec3 base = m0.rgb;
    float metallic = m1.w, roughness = m3.x;
    vec3 emissive = m1.rgb;
    vec2 uv;
    if (slotUv(m, tri, slotOf(m4.x), w, uv)) base *= sampleTexture(slotOf(m4.x).x, uv, true).rgb;
    if (slotUv(m, tri, slotOf(m4.y), w, uv)) {
      vec2 mr = applyMetallicRoughnessTexel(metallic, roughness,
                                            sampleTexture(slotOf(m4.y).x, uv, false));
      metallic = mr.x;
      roughness = mr.y;
    }
    if (slotUv(m, tri, slotOf(m4.w), w, uv))
      emissive *= sampleTexture(slotOf(m4.w).x, uv, true).rgb;
    p.sheenColor = m2.rgb;
    p.sheenRoughness = m2.w;
    if (slotUv(m, tri, slotOf(m5.x), w, uv))
      p.sheenColor *= sampleTexture(slotOf(m5.x).x, uv, true).rgb;
    if (slotUv(m, tri, slotOf(m5.y), w, uv))
      p.sheenRoughness *= sampleTexture(slotOf(m5.y).x, uv, false).a;
    p.sheenRoughness = clamp(p.sheenRoughness, 0.0, 1.0);
    if ((m.flags & 1u) != 0u && slotUv(m, tri, slotOf(m4.z), w, uv)) {
      vec4 t4 = vertexAt(tri.x, 2) * w.x + vertexAt(tri.y, 2) * w.y + vertexAt(tri.z, 2) * w.z;
      n = applyNormalMap(n, t4, sampleTexture(slotOf(m4.z).x, uv, false), m3.y);
    }
    p.baseColor = base;
    p.metallic = clamp(metallic, 0.0, 1.0);
    p.roughness = clamp(roughness, 0.0, 1.0);
    p.emissive = emissive;
  }
  if (hit.sphere) {
    vec4 m0 = materialAt(material, 0), m1 = materialAt(material, 1), m2 = materialAt(material, 2);
    p.baseColor = m0.rgb;
    p.metallic = m1.w;
    p.roughness = materialAt(material, 3).x;
    p.emissive = m1.rgb;
    p.sheenColor = m2.rgb;
    p.sheenRoughness = m2.w;
  }
  // Shade the side the ray sees.
  if (dot(n, dir) > 0.0) n = -n;
  p.normal = n;
  return p;
}

bool materialEmits(SceneHit hit) {
  uint material = hit.sphere ? floatBitsToUint(sceneData[params.offsets2.x + 2u * hit.mesh + 1u].x)
                             : meshAt(hit.mesh).material;
  return materialAt(material, 1).rgb != vec3(0.0);
}

// --- Lights ---

// Light i's record (ibl/shared/light_record.h; uploadScene in src/gpu/path_tracer.cpp).
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
  int n = environmentSize();
  int base = 6 * n + 6 * n * n + 2 * 33 * 33 + int(table) * kIesRows * kIesColumns;
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

bool unoccluded(vec3 origin, vec3 w, float distance) {
  return !flag(kFlagVisibility) ||
         !occluded(origin, w, distance < kInfinity * 0.5 ? distance * (1.0 - 1e-4) : kInfinity);
}

vec3 tracePath(Surface p, vec3 position, vec3 view, inout PathSampler numbers) {
  vec3 sum = vec3(0.0), throughput = vec3(1.0);
  for (int depth = 0;; ++depth) {
    if (depth == 0) sum += throughput * p.emissive;
    mat3 frame = tangentFrame(p.normal);
    mat3 toLocal = transpose(frame);
    vec3 v = toLocal * view;
    // A probe capture leaves out the view-dependent specular of the surfaces the camera sees.
    bool captured = depth == 0 && !flag(kFlagCameraSeesSpecular);
    int lobes = captured ? kLobesDiffuse : params.path.y;
    if (captured && flag(kFlagCaptureMetalsAsDiffuse)) {
      vec3 f0 = mix(vec3(0.04), p.baseColor, p.metallic);
      p.baseColor = p.baseColor * (1.0 - p.metallic) + p.metallic * f0;
      p.metallic = 0.0;
    }
    PathBrdf brdf = pathBrdfOf(p.baseColor, p.metallic, p.roughness, p.sheenColor,
                               p.sheenRoughness, v, lobes, pathShading());
    vec3 origin = position + p.normal * 1e-4 * max(1.0, length(position));
    // Next-event estimation: one sample of each light, of the emitters and of the environment.
    for (uint i = 0u; i < params.counts.x; ++i) {
      ShadingLight light = lightAt(i);
      vec2 xi = pathUniform2(numbers);
      vec3 direction, radiance;
      float distance, pdf;
      bool delta = light.type == kLightPoint || light.type == kLightSpot;
      if (delta) {
        vec3 d = light.position - origin;
        distance = length(d);
        direction = d / distance;
        radiance = light.color * punctualLightIrradiance(light, origin);
        float ies = lightRecordProfile(lightRecordAt(i));
        if (ies >= 0.0) radiance *= iesIntensity(light, ies, -direction);
        pdf = 0.0;
      } else {
        AreaLightSample ls = sampleAreaLight(light, origin, xi);
        direction = ls.direction;
        distance = ls.distance;
        radiance = ls.radiance * lightRangeWindow(light, origin);
        pdf = ls.pdf;
      }
      if (!(delta || pdf > 0.0) || radiance == vec3(0.0)) continue;
      vec3 l = toLocal * direction;
      if (l.z <= 0.0 || !unoccluded(origin, direction, distance)) continue;
      float weight = delta ? 1.0 : powerHeuristic(pdf, pathBrdfPdf(brdf, v, l)) / pdf;
      sum += throughput * evaluatePathBrdf(brdf, v, l, numbers, true) * radiance * weight;
    }
    if (params.counts.z > 0u) {
      float pick = pathUniform(numbers);
      vec2 point = pathUniform2(numbers);
      EmitterSample es = sampleEmitters(origin, vec3(pick, point));
      vec3 l = toLocal * es.direction;
      if (es.pdf > 0.0 && es.radiance != vec3(0.0) && l.z > 0.0 &&
          unoccluded(origin, es.direction, es.distance)) {
        float ld;
        vec3 lr;
        if (!(nearestLight(origin, es.direction, ld, lr) >= 0 && ld < es.distance)) {
          float weight = flag(kFlagVisibility)
                             ? powerHeuristic(es.pdf, pathBrdfPdf(brdf, v, l)) / es.pdf
                             : 1.0 / es.pdf;
          sum += throughput * evaluatePathBrdf(brdf, v, l, numbers, true) * es.radiance * weight;
        }
      }
    }
    if (flag(kFlagEnvironmentLight)) {
      vec3 w = sampleEnvironment(pathUniform2(numbers));
      vec3 l = toLocal * w;
      float pe = environmentPdf(w);
      float ld;
      vec3 lr;
      if (l.z > 0.0 && pe > 0.0 && nearestLight(origin, w, ld, lr) < 0 &&
          unoccluded(origin, w, kInfinity))
        sum += throughput * evaluatePathBrdf(brdf, v, l, numbers, true) * environmentRadiance(w) *
               (powerHeuristic(pe, pathBrdfPdf(brdf, v, l)) / pe);
    }
    // The BRDF's sample: it ends on a light or the environment, or goes on from what it meets.
    PathBrdfSample bs = samplePathBrdf(brdf, v, numbers);
    vec3 l = bs.direction;
    float pb = pathBrdfPdf(brdf, v, l);
    if (!(pb > 0.0) || bs.weight == vec3(0.0)) break;
    vec3 w = frame * l;
    vec3 f = bs.weight * pb;
    SceneHit hit = flag(kFlagVisibility) ? intersectScene(origin, w, kInfinity, false)
                                         : SceneHit(false, kInfinity, false, 0u, 0u, 0.0, 0.0);
    float ld;
    vec3 lr;
    int seen = nearestLight(origin, w, ld, lr);
    if (seen >= 0 && (!hit.found || ld < hit.t)) {
      ShadingLight light = lightAt(uint(seen));
      float pl = areaLightPdf(light, origin, w);
      sum += throughput * f * lr * lightRangeWindow(light, position) * (powerHeuristic(pb, pl) / pb);
      break;
    }
    if (!hit.found) {
      if (flag(kFlagEnvironmentLight))
        sum += throughput * f * environmentRadiance(w) *
               (powerHeuristic(pb, environmentPdf(w)) / pb);
      break;
    }
    Surface next;
    bool haveNext = false;
    if (materialEmits(hit)) {
      next = surfaceAt(hit, origin, w);
      haveNext = true;
      float pe = hit.sphere || params.counts.z == 0u ? 0.0 : emitterPdf(w, hit.t, hit.mesh, hit.primitive);
      sum += throughput * f * next.emissive * (powerHeuristic(pb, pe) / pb);
    }
    if (depth >= params.path.x) break;
    throughput *= f / pb;
    // Russian roulette after two bounces: go on with the probability of the throughput.
    if (depth >= 1) {
      float q = min(max(throughput.x, max(throughput.y, throughput.z)), 0.95);
      if (!(pathUniform(numbers) < q)) break;
      throughput /= q;
    }
    p = haveNext ? next : surfaceAt(hit, origin, w);
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
