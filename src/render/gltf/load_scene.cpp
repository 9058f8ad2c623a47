// The scene: the node tree walked from the rendered scene's roots, each mesh instance placed in
// the world (normals and tangents generated where it lacks them), the first camera and the
// lights; the names each instance answers to.
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "document.hpp"
#include "render/mesh_tangents.hpp"

namespace ibl::gltf {

namespace {

glm::mat4 nodeTransform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(node.matrix[i]);
    return m;
  }
  glm::mat4 t(1.0f), r(1.0f), s(1.0f);
  if (node.translation.size() == 3)
    t[3] =
        glm::vec4(static_cast<float>(node.translation[0]), static_cast<float>(node.translation[1]),
                  static_cast<float>(node.translation[2]), 1.0f);
  if (node.rotation.size() == 4)
    r = glm::mat4_cast(
        glm::quat(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                  static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2])));
  if (node.scale.size() == 3)
    s = glm::scale(glm::mat4(1.0f),
                   glm::vec3(static_cast<float>(node.scale[0]), static_cast<float>(node.scale[1]),
                             static_cast<float>(node.scale[2])));
  return t * r * s;
}

// The UV set (0 or 1) that gives a mesh of material m its tangents, or -1 where it needs none:
// the normal map's, else KHR_materials_clearcoat's (which asks a tangent space too), else, for
// KHR_materials_anisotropy (whose direction lies in the tangent frame), its texture's or
// TEXCOORD_0.
int tangentSource(const Material& m) {
  if (m.normalTexture.index >= 0) return m.normalTexture.texCoord;
  if (m.clearcoatNormalTexture.index >= 0) return m.clearcoatNormalTexture.texCoord;
  if (m.anisotropy > 0.0f) return m.anisotropyTexture.index >= 0 ? m.anisotropyTexture.texCoord : 0;
  return -1;
}

// Moves a mesh to world space; generates the normals it lacks, and the tangents it lacks when
// its material needs them (tangentSource: texCoord >= 0), from that UV set.
void placeInWorld(Mesh& mesh, const glm::mat4& world, int texCoord) {
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(world)));
  for (auto& p : mesh.positions) p = glm::vec3(world * glm::vec4(p, 1.0f));
  if (mesh.normals.empty()) {
    mesh.normals = generateNormals(mesh);
  } else {
    for (auto& n : mesh.normals) n = glm::normalize(normalMatrix * n);
  }
  // The file's tangents move with the mesh (KHR_materials_anisotropy reads them without UVs).
  for (auto& t : mesh.tangents) {
    const glm::vec3 moved = glm::mat3(world) * glm::vec3(t);
    const float length = glm::length(moved);
    t = glm::vec4(length > 0.0f ? moved / length : moved, t.w);  // a zero tangent stays zero
  }
  const std::vector<glm::vec2>& uvs = texCoord == 1 ? mesh.uvs1 : mesh.uvs;
  if (mesh.tangents.empty() && !uvs.empty() && texCoord >= 0)
    mesh.tangents = generateTangents(mesh, uvs);
}

// A node's camera, placed by the node's world transform.
CameraDescription cameraOf(const tinygltf::Camera& c, const glm::mat4& world) {
  CameraDescription d;
  d.perspective = c.type != "orthographic";
  d.yfovRadians = static_cast<float>(c.perspective.yfov);
  d.xmag = static_cast<float>(c.orthographic.xmag);
  d.world = world;
  return d;
}

}  // namespace

Scene GltfDocument::load() {
  Scene scene;
  scene.textures = readTextures(true);
  scene.materials = readMaterials(scene.textures);
  std::vector<std::size_t> uses(model_.meshes.size(), 0);
  for (const Instance& i : instances_) ++uses[static_cast<std::size_t>(nodes()[i.node].mesh)];
  prepareGeometry(uses);
  const int defaultMaterial = static_cast<int>(scene.materials.size()) - 1;
  for (const Instance& instance : instances_) {
    const int m = nodes()[instance.node].mesh;
    const std::size_t prims = model_.meshes[static_cast<std::size_t>(m)].primitives.size();
    for (std::size_t p = 0; p < prims; ++p) {
      PrimitiveData* data = primitive(m, p);
      if (!data) continue;
      Mesh mesh;
      if (--data->instancesLeft == 0)
        mesh = std::move(data->mesh);  // its last instance
      else
        mesh = data->mesh;
      const int material = materialOf(m, p);
      mesh.material = material >= 0 ? material : defaultMaterial;
      mesh.names = namesOf(instance.node);
      mesh.thicknessScale = std::cbrt(std::abs(glm::determinant(glm::mat3(instance.world))));
      placeInWorld(mesh, instance.world,
                   tangentSource(scene.materials[static_cast<std::size_t>(mesh.material)]));
      checkFinite(mesh, m, p, instance.node);
      if (!mesh.indices.empty()) scene.meshes.push_back(std::move(mesh));
    }
  }
  if (camera_)
    scene.camera =
        cameraOf(model_.cameras[static_cast<std::size_t>(camera_->first)], camera_->second);
  for (const Instance& i : lightInstances_) scene.lights.push_back(lightOf(i));
  if (scene.meshes.empty()) fail(path_, "no triangle meshes to render");
  return scene;
}

std::vector<std::string> GltfDocument::namesOf(int node) const {
  std::vector<std::string> names;
  const std::string& mesh =
      model_.meshes[static_cast<std::size_t>(nodes()[static_cast<std::size_t>(node)].mesh)].name;
  if (!mesh.empty()) names.push_back(mesh);
  for (int at = node; at >= 0; at = parents_[static_cast<std::size_t>(at)])
    if (!nodes()[static_cast<std::size_t>(at)].name.empty())
      names.push_back(nodes()[static_cast<std::size_t>(at)].name);
  return names;
}

void GltfDocument::walkScene() {
  std::vector<int> roots;
  if (!model_.scenes.empty()) {
    sceneIndex_ = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    roots = model_.scenes[static_cast<std::size_t>(sceneIndex_)].nodes;
  } else {
    for (std::size_t n = 0; n < nodes().size(); ++n)
      if (parents_[n] == -1) roots.push_back(static_cast<int>(n));
  }
  inScene_.assign(nodes().size(), false);
  std::vector<std::pair<int, glm::mat4>> stack;
  for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.emplace_back(*r, glm::mat4(1.0f));
  while (!stack.empty()) {
    const auto [n, parent] = stack.back();
    stack.pop_back();
    const tinygltf::Node& node = nodes()[static_cast<std::size_t>(n)];
    inScene_[static_cast<std::size_t>(n)] = true;
    const glm::mat4 world = parent * nodeTransform(node);
    if (node.camera >= 0 && !camera_) camera_ = std::make_pair(node.camera, world);
    if (node.mesh >= 0) instances_.push_back({n, world});
    if (lightIndexOf(node) >= 0) lightInstances_.push_back({n, world});
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
      stack.emplace_back(*c, world);
  }
}

}  // namespace ibl::gltf
