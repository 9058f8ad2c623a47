// What `ibl info` reports of a file (GltfSummary): the nodes, every mesh read once for its
// counts, the scene's instances and bounds, the materials, textures (checked, not decoded),
// lights and cameras, and the warnings.
#include <algorithm>
#include <limits>
#include <set>

#include <glm/common.hpp>

#include "document.hpp"
#include "ibl/shared/material.h"

namespace ibl::gltf {

GltfSummary GltfDocument::describe() {
  GltfSummary s;
  s.binary = binary_;
  s.generator = model_.asset.generator;
  s.extensionsUsed = model_.extensionsUsed;
  s.extensionsRequired = model_.extensionsRequired;
  s.scene = sceneIndex_;
  s.scenes = model_.scenes.size();
  s.variants = variants_;
  for (std::size_t n = 0; n < nodes().size(); ++n) {
    const tinygltf::Node& node = nodes()[n];
    s.nodes.push_back(
        {node.name, node.mesh, node.camera, lightIndexOf(node), parents_[n], inScene_[n]});
  }
  // Every mesh is read (one instance each at least, for the memory estimate), its counts of
  // one instance reported; the scene's totals and bounds count its instances.
  std::vector<std::size_t> uses(model_.meshes.size(), 0);
  for (const Instance& i : instances_) ++uses[static_cast<std::size_t>(nodes()[i.node].mesh)];
  std::vector<std::size_t> atLeastOnce = uses;
  for (auto& u : atLeastOnce) u = std::max<std::size_t>(u, 1);
  prepareGeometry(atLeastOnce);
  for (std::size_t m = 0; m < model_.meshes.size(); ++m) {
    const tinygltf::Mesh& mesh = model_.meshes[m];
    GltfSummary::Mesh info;
    info.name = mesh.name;
    info.primitives = mesh.primitives.size();
    info.instances = uses[m];
    std::set<std::string> compression;
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      if (prim.extensions.count("KHR_draco_mesh_compression"))
        compression.insert("KHR_draco_mesh_compression");
      for (const auto& [name, accessor] : prim.attributes)
        if (meshoptViews_.count(accessors()[static_cast<std::size_t>(accessor)].bufferView))
          compression.insert("EXT_meshopt_compression");
      if (prim.indices >= 0 &&
          meshoptViews_.count(accessors()[static_cast<std::size_t>(prim.indices)].bufferView))
        compression.insert("EXT_meshopt_compression");
      const PrimitiveData* data = primitive(static_cast<int>(m), p);
      if (!data) continue;
      ++info.trianglePrimitives;
      info.triangles += data->mesh.indices.size() / 3;
      info.vertices += data->mesh.positions.size();
      info.vertexColors = info.vertexColors || !data->mesh.colors.empty();
    }
    info.compression.assign(compression.begin(), compression.end());
    s.meshes.push_back(std::move(info));
  }
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (const Instance& instance : instances_) {
    const int m = nodes()[instance.node].mesh;
    for (std::size_t p = 0; p < model_.meshes[static_cast<std::size_t>(m)].primitives.size(); ++p) {
      const PrimitiveData* data = primitive(m, p);
      if (!data || data->mesh.indices.empty()) continue;
      ++s.meshInstances;
      s.triangles += data->mesh.indices.size() / 3;
      s.vertices += data->mesh.positions.size();
      for (const glm::vec3& v : data->mesh.positions) {
        const glm::vec3 w = glm::vec3(instance.world * glm::vec4(v, 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
      }
    }
  }
  if (s.triangles > 0) {
    s.hasBounds = true;
    s.boundsMin = lo;
    s.boundsMax = hi;
  }
  readTextures(false);  // the warnings about them
  for (std::size_t k = 0; k < model_.materials.size(); ++k) {
    const tinygltf::Material& m = model_.materials[k];
    GltfSummary::Material info;
    info.name = m.name;
    const auto& pbr = m.pbrMetallicRoughness;
    for (int c = 0; c < 4; ++c)
      info.baseColor[c] = static_cast<float>(pbr.baseColorFactor[static_cast<std::size_t>(c)]);
    info.metallic = static_cast<float>(pbr.metallicFactor);
    info.roughness = static_cast<float>(pbr.roughnessFactor);
    info.emissive = emissiveOf(m);
    info.alphaMode = m.alphaMode.empty() ? "OPAQUE" : m.alphaMode;
    info.doubleSided = m.doubleSided;
    for (const SlotRef& slot : materialSlots(m, path_, materialLabel(k))) {
      if (slot.index >= 0 &&
          std::find(info.textures.begin(), info.textures.end(), slot.index) == info.textures.end())
        info.textures.push_back(slot.index);
      if (slot.index >= 0 && slot.transformed) info.transformedSlots.push_back(slot.name);
    }
    Material factors;
    readExtensionFactors(m, path_, materialLabel(k), factors);
    info.ior = factors.ior;
    info.specular = factors.specular;
    info.specularColor = factors.specularColor;
    info.clearcoat = factors.clearcoat;
    info.clearcoatRoughness = factors.clearcoatRoughness;
    info.iridescence = factors.iridescence;
    info.iridescenceIor = factors.iridescenceIor;
    info.iridescenceThicknessMinimum = factors.iridescenceThicknessMinimum;
    info.iridescenceThicknessMaximum = factors.iridescenceThicknessMaximum;
    info.anisotropy = factors.anisotropy;
    info.anisotropyRotation = factors.anisotropyRotation;
    info.transmission = factors.transmission;
    info.thickness = factors.thickness;
    info.attenuationDistance = factors.attenuationDistance;
    info.attenuationColor = factors.attenuationColor;
    const shared::SpecularReflectance dielectric = shared::specularReflectance(
        glm::vec3(0.0f), 0.0f, factors.ior, factors.specular, factors.specularColor, false);
    info.dielectricF0 = dielectric.f0;
    info.dielectricF90 = dielectric.f90;
    for (const auto& [name, value] : m.extensions) {
      info.extensions.push_back(name);
      if (!implemented(name)) info.unsupported.push_back(name);
    }
    s.materials.push_back(std::move(info));
  }
  for (std::size_t t = 0; t < model_.textures.size(); ++t) {
    GltfSummary::Texture info;
    info.image = textureImage(static_cast<int>(t));
    info.used = usedTextures_.count(static_cast<int>(t)) > 0;
    if (info.image >= 0) {
      const ImageSource& src = images_[static_cast<std::size_t>(info.image)];
      info.source = sourceName(info.image);
      info.mimeType = src.mimeType;
      const ImageState& state = imageState(info.image);
      info.width = state.probe.width;
      info.height = state.probe.height;
      info.problem = state.missing ? "missing" : state.probe.problem;
    } else {
      info.problem = noSourceProblem(static_cast<int>(t));
    }
    s.textures.push_back(std::move(info));
  }
  std::vector<std::size_t> lightUses(model_.lights.size(), 0), cameraUses(model_.cameras.size(), 0);
  for (const Instance& i : lightInstances_)
    ++lightUses[static_cast<std::size_t>(lightIndexOf(nodes()[i.node]))];
  for (std::size_t n = 0; n < nodes().size(); ++n)
    if (inScene_[n] && nodes()[n].camera >= 0)
      ++cameraUses[static_cast<std::size_t>(nodes()[n].camera)];
  for (std::size_t k = 0; k < model_.lights.size(); ++k) {
    const tinygltf::Light& l = model_.lights[k];
    GltfSummary::Light info;
    info.name = l.name;
    info.type = l.type;
    info.intensity = l.intensity;
    if (l.color.size() == 3)
      info.color = glm::vec3(static_cast<float>(l.color[0]), static_cast<float>(l.color[1]),
                             static_cast<float>(l.color[2]));
    info.range = l.range;
    info.innerConeAngle = l.spot.innerConeAngle;
    info.outerConeAngle = l.spot.outerConeAngle;
    info.instances = lightUses[k];
    s.lights.push_back(std::move(info));
  }
  for (std::size_t k = 0; k < model_.cameras.size(); ++k) {
    const tinygltf::Camera& c = model_.cameras[k];
    GltfSummary::Camera info;
    info.name = c.name;
    info.type = c.type;
    if (c.type == "orthographic") {
      info.xmag = c.orthographic.xmag;
      info.ymag = c.orthographic.ymag;
      info.znear = c.orthographic.znear;
      info.zfar = c.orthographic.zfar;
    } else {
      info.yfov = c.perspective.yfov;
      info.aspectRatio = c.perspective.aspectRatio;
      info.znear = c.perspective.znear;
      info.zfar = c.perspective.zfar;
    }
    info.instances = cameraUses[k];
    s.cameras.push_back(std::move(info));
  }
  s.warnings = warnings_;
  return s;
}

}  // namespace ibl::gltf
