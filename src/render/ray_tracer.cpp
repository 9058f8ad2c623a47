#include "ray_tracer.hpp"

#include <algorithm>
#include <cstdint>

#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/shared/material.h"
#include "ibl/shared/specular_antialiasing.h"
#include "ibl/shared/transmission.h"

namespace ibl {

namespace {

// The UV at which texture slot `ref` reads a surface point of UV `uv` in its set
// (KHR_texture_transform's map, shared::uvTransformOf).
glm::vec2 slotUv(const TextureRef& ref, glm::vec2 uv) {
  if (ref.transform.identity()) return uv;
  const TextureTransform& t = ref.transform;
  return shared::transformUv(shared::uvTransformOf(t.offset, t.rotation, t.scale), uv);
}

// The material's alpha at a hit (barycentrics u, v of triangle `primitive`).
float alphaAt(const AlphaTest& a, unsigned primitive, float u, float v) {
  float alpha = a.material->baseColorAlpha;
  const std::uint32_t* i = &a.mesh->indices[3 * static_cast<std::size_t>(primitive)];
  const std::vector<glm::vec2>& uvs =
      a.material->baseColorTexture.texCoord == 1 ? a.mesh->uvs1 : a.mesh->uvs;
  if (a.texture && !uvs.empty()) {
    const glm::vec2 uv = uvs[i[0]] * (1.0f - u - v) + uvs[i[1]] * u + uvs[i[2]] * v;
    alpha *= a.texture->sample(slotUv(a.material->baseColorTexture, uv), false).w;
  }
  const std::vector<glm::vec4>& colors = a.mesh->colors;
  if (!colors.empty())
    alpha *= colors[i[0]].w * (1.0f - u - v) + colors[i[1]].w * u + colors[i[2]].w * v;
  return alpha;
}

// Embree's filter for MASK and BLEND meshes, of intersections and of occlusion alike: a hit the
// alpha does not cover is ignored, and the ray goes on.
void alphaFilter(const RTCFilterFunctionNArguments* args) {
  const auto* a = static_cast<const AlphaTest*>(args->geometryUserPtr);
  for (unsigned k = 0; k < args->N; ++k) {
    if (args->valid[k] != -1) continue;
    const unsigned primitive = RTCHitN_primID(args->hit, args->N, k);
    const float alpha =
        alphaAt(*a, primitive, RTCHitN_u(args->hit, args->N, k), RTCHitN_v(args->hit, args->N, k));
    const glm::vec3 origin(RTCRayN_org_x(args->ray, args->N, k),
                           RTCRayN_org_y(args->ray, args->N, k),
                           RTCRayN_org_z(args->ray, args->N, k));
    const glm::vec3 dir(RTCRayN_dir_x(args->ray, args->N, k), RTCRayN_dir_y(args->ray, args->N, k),
                        RTCRayN_dir_z(args->ray, args->N, k));
    if (!shared::alphaCovers(static_cast<int>(a->material->alphaMode), alpha,
                             a->material->alphaCutoff,
                             shared::rayBlendThreshold(origin, dir, primitive)))
      args->valid[k] = 0;
  }
}

}  // namespace

RTCRay embreeRay(glm::vec3 origin, glm::vec3 dir) {
  RTCRay ray{};
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.dir_x = dir.x;
  ray.dir_y = dir.y;
  ray.dir_z = dir.z;
  ray.tnear = 0.0f;
  ray.tfar = INFINITY;
  ray.mask = 0xffffffffu;
  return ray;
}

unsigned RayTracer::maskOf(const Material& material) {
  return material.transmission > 0.0f ? kTransmissive : kOpaque;
}

RayTracer::RayTracer(const Scene& scene) : scene_(scene), transmits_(hasTransmission(scene)) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) fail("embree", "cannot create a device");
  handle_ = rtcNewScene(device_);
  rtcSetSceneFlags(handle_, RTC_SCENE_FLAG_COMPACT);
  alphaTests_.reserve(scene.meshes.size());  // stable addresses: Embree keeps pointers
  for (const Mesh& m : scene.meshes) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.positions.size()));
    for (std::size_t i = 0; i < m.positions.size(); ++i)
      for (int c = 0; c < 3; ++c) v[3 * i + c] = m.positions[i][c];
    // The scene outlives the tracer: Embree reads the mesh's triangles where they are.
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0,
                               3 * sizeof(std::uint32_t), m.indices.size() / 3);
    const Material& mat = scene.materials[m.material];
    if (mat.alphaMode != AlphaMode::Opaque) {
      const int t = mat.baseColorTexture.index;
      alphaTests_.push_back({&m, &mat, t >= 0 ? &scene.textures[t] : nullptr});
      rtcSetGeometryUserData(g, &alphaTests_.back());
      rtcSetGeometryIntersectFilterFunction(g, alphaFilter);
      rtcSetGeometryOccludedFilterFunction(g, alphaFilter);
    }
    rtcSetGeometryMask(g, maskOf(mat));
    rtcCommitGeometry(g);
    rtcAttachGeometry(handle_, g);
    rtcReleaseGeometry(g);
  }
  // The spheres in two geometries, those that transmit nothing and those that transmit (each
  // its mask), their primitives mapped back to the scene's spheres.
  for (int transmits = 0; transmits < 2; ++transmits) {
    std::vector<std::uint32_t>& spheres = sphereIndices_[transmits];
    for (std::size_t i = 0; i < scene.spheres.size(); ++i)
      if ((maskOf(scene.materials[static_cast<std::size_t>(scene.spheres[i].material)]) ==
           kTransmissive) == (transmits == 1))
        spheres.push_back(static_cast<std::uint32_t>(i));
    if (spheres.empty()) continue;
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), spheres.size()));
    for (std::size_t i = 0; i < spheres.size(); ++i) {
      const Sphere& s = scene.spheres[spheres[i]];
      for (int c = 0; c < 3; ++c) v[4 * i + c] = s.center[c];
      v[4 * i + 3] = s.radius;
    }
    rtcSetGeometryMask(g, transmits == 1 ? kTransmissive : kOpaque);
    rtcCommitGeometry(g);
    sphereGeometries_[transmits] = rtcAttachGeometry(handle_, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(handle_);
}

const Material& hitMaterial(const Scene& scene, const RayTracer& tracer,
                            const RayTracer::Hit& hit) {
  const int material = tracer.isSphere(hit.geometry) ? scene.spheres[hit.primitive].material
                                                     : scene.meshes[hit.geometry].material;
  return scene.materials[static_cast<std::size_t>(material)];
}

RayTracer::Hit hitOnSameSurface(const Scene& scene, const RayTracer& tracer,
                                const RayTracer::Hit& hit, const Ray& ray) {
  RayTracer::Hit h = hit;
  if (tracer.isSphere(hit.geometry)) {
    const Sphere& s = scene.spheres[hit.primitive];
    const glm::vec3 oc = ray.origin - s.center;
    const float b = glm::dot(oc, ray.direction);
    const float disc = b * b - (glm::dot(oc, oc) - s.radius * s.radius);
    // The first intersection in front of the ray's origin (the far one from inside), as the
    // viewer's intersectSphere; the nearest point where it misses.
    const float root = std::sqrt(std::max(disc, 0.0f));
    h.t = disc < 0.0f ? -b : (-b - root >= 0.0f ? -b - root : -b + root);
    return h;
  }
  // Moller & Trumbore 1997 without the bounds on the barycentrics.
  const Mesh& m = scene.meshes[hit.geometry];
  const glm::vec3 p0 = m.positions[m.indices[3 * hit.primitive]],
                  e1 = m.positions[m.indices[3 * hit.primitive + 1]] - p0,
                  e2 = m.positions[m.indices[3 * hit.primitive + 2]] - p0;
  const glm::vec3 q = glm::cross(ray.direction, e2);
  const float inverse = 1.0f / glm::dot(e1, q);
  const glm::vec3 o = ray.origin - p0;
  const glm::vec3 r = glm::cross(o, e1);
  h.u = glm::dot(o, q) * inverse;
  h.v = glm::dot(ray.direction, r) * inverse;
  h.t = glm::dot(e2, r) * inverse;
  return h;
}

SurfacePoint surfaceAt(const Scene& scene, const RayTracer& tracer, const RayTracer::Hit& hit,
                       const Ray& ray) {
  SurfacePoint p{};
  const Material* mat;
  glm::vec3 n, coatNormal;
  // KHR_materials_anisotropy: the tangent frame, and the texel (the extension's default without
  // a texture).
  glm::vec4 tangent(0.0f), anisotropyTexel(1.0f, 0.5f, 1.0f, 1.0f);
  if (tracer.isSphere(hit.geometry)) {
    const Sphere& s = scene.spheres[hit.primitive];
    n = glm::normalize(ray.origin + hit.t * ray.direction - s.center);
    mat = &scene.materials[s.material];
    p.baseColor = mat->baseColor;
    p.metallic = mat->metallic;
    p.roughness = mat->roughness;
    p.emissive = mat->emissive;
    p.sheenColor = mat->sheenColor;
    p.sheenRoughness = mat->sheenRoughness;
    p.specular = mat->specular;
    p.specularColor = mat->specularColor;
    p.clearcoat = mat->clearcoat;
    p.clearcoatRoughness = mat->clearcoatRoughness;
    p.iridescence = mat->iridescence;
    p.iridescenceThickness = mat->iridescenceThicknessMaximum;
    p.transmission = mat->transmission;
    p.thickness = mat->thickness;
    coatNormal = n;
    tangent = shared::sphereTangent(n);
  } else {
    const Mesh& m = scene.meshes[hit.geometry];
    mat = &scene.materials[m.material];
    const std::uint32_t i0 = m.indices[3 * hit.primitive], i1 = m.indices[3 * hit.primitive + 1],
                        i2 = m.indices[3 * hit.primitive + 2];
    const float w0 = 1.0f - hit.u - hit.v, w1 = hit.u, w2 = hit.v;
    n = glm::normalize(m.normals[i0] * w0 + m.normals[i1] * w1 + m.normals[i2] * w2);
    // The side the ray meets: the triangle's own plane, turned to its normals' side (an
    // interpolated normal leans past the ray at a smooth mesh's silhouette).
    glm::vec3 face =
        glm::cross(m.positions[i1] - m.positions[i0], m.positions[i2] - m.positions[i0]);
    if (glm::dot(face, m.normals[i0] + m.normals[i1] + m.normals[i2]) < 0.0f) face = -face;
    const float area2 = glm::dot(face, face);
    p.faceNormal = area2 > 0.0f ? face / std::sqrt(area2) : n;
    p.frontFace = glm::dot(p.faceNormal, ray.direction) <= 0.0f;
    glm::vec3 base = mat->baseColor;
    float metallic = mat->metallic, roughness = mat->roughness;
    glm::vec3 emissive = mat->emissive;
    // Each slot reads its own UV set (glTF texCoord); a slot whose set the mesh lacks is off.
    const auto lookup = [&](const TextureRef& ref, bool srgb, glm::vec4& texel) {
      const std::vector<glm::vec2>& uvs = ref.texCoord == 1 ? m.uvs1 : m.uvs;
      if (ref.index < 0 || uvs.empty()) return false;
      const glm::vec2 uv = uvs[i0] * w0 + uvs[i1] * w1 + uvs[i2] * w2;
      texel = scene.textures[ref.index].sample(slotUv(ref, uv), srgb);
      return true;
    };
    glm::vec4 t;
    if (lookup(mat->baseColorTexture, true, t)) base *= glm::vec3(t);
    if (!m.colors.empty()) {
      const glm::vec3 color(m.colors[i0] * w0 + m.colors[i1] * w1 + m.colors[i2] * w2);
      base *= color;
      if (mat->unlit) emissive *= color;  // the base color, moved to the emission
    }
    if (lookup(mat->metallicRoughnessTexture, false, t)) {
      const glm::vec2 mr = shared::applyMetallicRoughnessTexel(metallic, roughness, t);
      metallic = mr.x;
      roughness = mr.y;
    }
    if (lookup(mat->occlusionTexture, false, t)) {
      p.occlusion = shared::occlusionFromTexel(mat->occlusionStrength, t);
      p.occlusionTexture = true;
    }
    if (lookup(mat->emissiveTexture, true, t)) emissive *= glm::vec3(t);
    p.sheenColor = mat->sheenColor;
    p.sheenRoughness = mat->sheenRoughness;
    if (lookup(mat->sheenColorTexture, true, t)) p.sheenColor *= glm::vec3(t);
    if (lookup(mat->sheenRoughnessTexture, false, t)) p.sheenRoughness *= t.w;
    p.sheenRoughness = std::clamp(p.sheenRoughness, 0.0f, 1.0f);
    p.specular = mat->specular;
    p.specularColor = mat->specularColor;
    if (lookup(mat->specularTexture, false, t)) p.specular *= t.w;
    if (lookup(mat->specularColorTexture, true, t)) p.specularColor *= glm::vec3(t);
    p.clearcoat = mat->clearcoat;
    p.clearcoatRoughness = mat->clearcoatRoughness;
    if (lookup(mat->clearcoatTexture, false, t)) p.clearcoat *= t.x;
    if (lookup(mat->clearcoatRoughnessTexture, false, t)) p.clearcoatRoughness *= t.y;
    p.clearcoat = std::clamp(p.clearcoat, 0.0f, 1.0f);
    p.clearcoatRoughness = std::clamp(p.clearcoatRoughness, 0.0f, 1.0f);
    p.iridescence = mat->iridescence;
    if (lookup(mat->iridescenceTexture, false, t)) p.iridescence *= t.x;
    p.iridescence = std::clamp(p.iridescence, 0.0f, 1.0f);
    p.iridescenceThickness = mat->iridescenceThicknessMaximum;
    if (lookup(mat->iridescenceThicknessTexture, false, t))
      p.iridescenceThickness =
          glm::mix(mat->iridescenceThicknessMinimum, mat->iridescenceThicknessMaximum, t.y);
    p.transmission = mat->transmission;
    if (lookup(mat->transmissionTexture, false, t)) p.transmission *= t.x;
    p.transmission = std::clamp(p.transmission, 0.0f, 1.0f);
    p.thickness = mat->thickness * m.thicknessScale;  // the node's scale (KHR_materials_volume)
    if (lookup(mat->thicknessTexture, false, t)) p.thickness *= t.y;
    // The coat's normal: the interpolated one, unless it has a normal map of its own (not the
    // base's: KHR_materials_clearcoat).
    coatNormal = n;
    if (!m.tangents.empty()) {
      tangent = m.tangents[i0] * w0 + m.tangents[i1] * w1 + m.tangents[i2] * w2;
      if (lookup(mat->clearcoatNormalTexture, false, t)) {
        coatNormal = shared::applyNormalMap(n, tangent, t, mat->clearcoatNormalScale);
        p.clearcoatNormalMapAlpha2 =
            shared::normalMapAlpha2(glm::vec3(t), mat->clearcoatNormalScale);
      }
      if (lookup(mat->normalTexture, false, t)) {
        n = shared::applyNormalMap(n, tangent, t, mat->normalScale);
        p.normalMapAlpha2 = shared::normalMapAlpha2(glm::vec3(t), mat->normalScale);
      }
    }
    lookup(mat->anisotropyTexture, false, anisotropyTexel);
    p.baseColor = base;
    p.metallic = std::clamp(metallic, 0.0f, 1.0f);
    p.roughness = std::clamp(roughness, 0.0f, 1.0f);
    p.emissive = emissive;
  }
  p.position = ray.origin + hit.t * ray.direction;
  // The anisotropy's direction in the frame of the side the mesh faces (a back face flips the
  // whole frame, as the glTF Sample Viewer does: the same line, the lobe is symmetric).
  const glm::vec3 anisotropy =
      shared::anisotropyDirectionOf(mat->anisotropyRotation, anisotropyTexel);
  p.anisotropy = std::clamp(mat->anisotropy * anisotropy.z, 0.0f, 1.0f);
  if (p.anisotropy > 0.0f)
    p.anisotropyTangent = shared::anisotropyTangentOf(n, tangent, glm::vec2(anisotropy));
  if (tracer.isSphere(hit.geometry)) {
    p.faceNormal = n;
    p.frontFace = glm::dot(n, ray.direction) <= 0.0f;
  }
  p.volume = mat->thickness > 0.0f && mat->ior > 0.0f;  // an infinite index: a thin wall
  if (p.volume)
    p.attenuation =
        shared::volumeAttenuationCoefficient(mat->attenuationColor, mat->attenuationDistance);
  // Shade the side the ray sees (the coat's normal on the same side).
  if (glm::dot(n, ray.direction) > 0.0f) {
    n = -n;
    coatNormal = -coatNormal;
  }
  p.ior = mat->ior;
  p.iridescenceIor = mat->iridescenceIor;
  p.normal = n;
  p.clearcoatNormal = coatNormal;
  // The coat lies over the emission too (KHR_materials_clearcoat, "Emission").
  if (p.clearcoat > 0.0f)
    p.emissive *= 1.0f - shared::clearcoatWeight(p.clearcoat, glm::dot(coatNormal, -ray.direction));
  return p;
}

}  // namespace ibl
