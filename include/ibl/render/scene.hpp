#pragma once
// Scenes to render: triangle meshes with glTF metallic-roughness materials (from glTF 2.0
// files), analytic spheres (the built-in scenes), and an optional camera.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "ibl/core/image.hpp"

namespace ibl {

// A texture: RGBA values in [0, 1] as stored (sRGB-encoded or linear, per its use).
struct Texture {
  int width = 0, height = 0;
  std::vector<glm::vec4> texels;
  glm::vec4 sample(glm::vec2 uv) const;  // bilinear, repeat wrapping
};

// glTF 2.0 metallic-roughness material (texture indices: -1 for none).
struct Material {
  glm::vec3 baseColor{1.0f};  // linear
  int baseColorTexture = -1;  // sRGB
  float metallic = 1.0f;
  float roughness = 1.0f;             // perceptual
  int metallicRoughnessTexture = -1;  // B = metallic, G = roughness (linear)
  int normalTexture = -1;
  float normalScale = 1.0f;
  int occlusionTexture = -1;  // R
  float occlusionStrength = 1.0f;
  glm::vec3 emissive{0.0f};
  int emissiveTexture = -1;  // sRGB
};

// Triangles in world space.
struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // per vertex
  std::vector<glm::vec4> tangents;  // per vertex, w = handedness (empty: no normal map)
  std::vector<glm::vec2> uvs;       // empty: no textures
  std::vector<std::uint32_t> indices;
  int material = 0;
};

struct Sphere {
  glm::vec3 center{0.0f};
  float radius = 1.0f;
  int material = 0;
};

struct CameraDescription {
  bool perspective = true;
  float yfovRadians = 0.8f;
  float xmag = 1.0f;      // orthographic half width
  glm::mat4 world{1.0f};  // camera looks down its -Z, +Y up
};

struct Scene {
  std::vector<Mesh> meshes;
  std::vector<Sphere> spheres;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::optional<CameraDescription> camera;

  // Axis-aligned bounds of everything.
  std::pair<glm::vec3, glm::vec3> bounds() const;
};

// One sphere of radius 1 at the origin.
Scene makeSphereScene(const Material& material);
// Spheres of roughness 0..1 (columns, left to right) x metallic 1 (top row) and 0 (bottom),
// radius 1, 2.5 apart, centered on the origin in the XY plane.
Scene makeSphereGrid(glm::vec3 baseColor, int columns = 6);

// A sphere as triangles for a rasterizer: `segments` around, segments / 2 from pole to pole,
// vertices on the sphere with exact normals.
Mesh tessellateSphere(const Sphere& sphere, int segments);

}  // namespace ibl
