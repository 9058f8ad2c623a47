#include "emissive_triangles.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "ibl/math/color.hpp"
#include "ray_tracer.hpp"

namespace ibl {

namespace {

// The mean linear luminance of an sRGB texture's RGB (what its texels scale the emission by).
float meanSrgbLuminance(const Texture& t) {
  if (t.empty()) return 1.0f;
  const std::vector<std::uint8_t>& rgba = *t.rgba;
  double sum = 0.0;
  for (std::size_t i = 0; i + 3 < rgba.size(); i += 4)
    sum += luminance(
        glm::vec3(srgb8ToLinear(rgba[i]), srgb8ToLinear(rgba[i + 1]), srgb8ToLinear(rgba[i + 2])));
  return static_cast<float>(sum / static_cast<double>(std::max<std::size_t>(rgba.size() / 4, 1)));
}

glm::vec3 vertex(const Mesh& m, unsigned primitive, int corner) {
  return m.positions[m.indices[3 * primitive + static_cast<unsigned>(corner)]];
}

}  // namespace

EmissiveTriangles::EmissiveTriangles(const Scene& scene, const RayTracer& tracer)
    : scene_(scene), tracer_(tracer), indexOf_(scene.meshes.size()) {
  std::vector<float> textureMean(scene.textures.size(), -1.0f);
  double total = 0.0;
  for (unsigned mi = 0; mi < scene.meshes.size(); ++mi) {
    const Mesh& m = scene.meshes[mi];
    const Material& mat = scene.materials[static_cast<std::size_t>(m.material)];
    // A MASK or BLEND emitter is not sampled (its alpha would have to be tested at the sampled
    // point): BRDF samples alone find it, with full weight (pdf() is 0 for it).
    if (mat.alphaMode != AlphaMode::Opaque) continue;
    float scale = luminance(mat.emissive);
    if (const int t = mat.emissiveTexture.index; t >= 0 && scale > 0.0f) {
      if (textureMean[static_cast<std::size_t>(t)] < 0.0f)
        textureMean[static_cast<std::size_t>(t)] =
            meanSrgbLuminance(scene.textures[static_cast<std::size_t>(t)]);
      scale *= textureMean[static_cast<std::size_t>(t)];
    }
    if (!(scale > 0.0f)) continue;
    const auto count = static_cast<unsigned>(m.indices.size() / 3);
    indexOf_[mi].assign(count, -1);
    for (unsigned p = 0; p < count; ++p) {
      const float area = 0.5f * glm::length(glm::cross(vertex(m, p, 1) - vertex(m, p, 0),
                                                       vertex(m, p, 2) - vertex(m, p, 0)));
      if (!(area > 0.0f)) continue;
      indexOf_[mi][p] = static_cast<std::int32_t>(triangles_.size());
      triangles_.push_back({mi, p, area});
      // The power a triangle emits from both faces is 2 pi L A: proportional to L A.
      total += static_cast<double>(scale) * area;
      cdf_.push_back(total);
    }
  }
  for (double& c : cdf_) c /= total;
}

EmitterSample EmissiveTriangles::sample(glm::vec3 p, glm::vec3 xi) const {
  EmitterSample s;
  if (triangles_.empty()) return s;
  const auto it = std::lower_bound(cdf_.begin(), cdf_.end(), static_cast<double>(xi.x));
  const auto i = static_cast<std::size_t>(
      std::min<std::ptrdiff_t>(it - cdf_.begin(), static_cast<std::ptrdiff_t>(cdf_.size()) - 1));
  const Triangle& tri = triangles_[i];
  const Mesh& m = scene_.meshes[tri.mesh];
  // Uniform over the triangle: b = (1 - sqrt(u), sqrt(u) (1 - v), sqrt(u) v) (pbrt-v4, 6.5.4's
  // square-root parameterization).
  const float su = std::sqrt(xi.y);
  const float b1 = su * (1.0f - xi.z), b2 = su * xi.z;
  const glm::vec3 a = vertex(m, tri.primitive, 0), e1 = vertex(m, tri.primitive, 1) - a,
                  e2 = vertex(m, tri.primitive, 2) - a;
  const glm::vec3 x = a + b1 * e1 + b2 * e2;
  const glm::vec3 d = x - p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return s;
  const float dist = std::sqrt(dist2);
  const glm::vec3 w = d / dist;
  const glm::vec3 ng = glm::normalize(glm::cross(e1, e2));
  const float cosLight = std::abs(glm::dot(ng, w));
  if (!(cosLight > 1e-6f)) return s;
  const double pTriangle = cdf_[i] - (i > 0 ? cdf_[i - 1] : 0.0);
  // Area density 1 / A to solid angle: times d^2 / |cos theta_light|.
  s.pdf = static_cast<float>(pTriangle) / tri.area * dist2 / cosLight;
  s.direction = w;
  s.distance = dist;
  RayTracer::Hit hit;
  hit.found = true;
  hit.t = dist;
  hit.geometry = tri.mesh;
  hit.primitive = tri.primitive;
  hit.u = b1;
  hit.v = b2;
  hit.ng = ng;
  s.radiance = surfaceAt(scene_, tracer_, hit, Ray{p, w}).emissive;
  return s;
}

float EmissiveTriangles::pdf(glm::vec3 w, float t, unsigned mesh, unsigned primitive) const {
  if (mesh >= indexOf_.size() || primitive >= indexOf_[mesh].size()) return 0.0f;
  const std::int32_t i = indexOf_[mesh][primitive];
  if (i < 0) return 0.0f;
  const Triangle& tri = triangles_[static_cast<std::size_t>(i)];
  const Mesh& m = scene_.meshes[mesh];
  const glm::vec3 a = vertex(m, primitive, 0);
  const glm::vec3 ng =
      glm::normalize(glm::cross(vertex(m, primitive, 1) - a, vertex(m, primitive, 2) - a));
  const float cosLight = std::abs(glm::dot(ng, w));
  if (!(cosLight > 1e-6f)) return 0.0f;
  const auto k = static_cast<std::size_t>(i);
  const double pTriangle = cdf_[k] - (k > 0 ? cdf_[k - 1] : 0.0);
  return static_cast<float>(pTriangle) / tri.area * t * t / cosLight;
}

}  // namespace ibl
