// KHR_materials_variants: the file's named variants (the root's list) and, per primitive, the
// material each variant gives it. The mappings are checked with the rest of the file
// (validateVariants); GltfLoadOptions::variant picks one, whose materials load() assigns.
#include <fmt/format.h>

#include "document.hpp"

namespace ibl::gltf {

namespace {

constexpr const char* kVariants = "KHR_materials_variants";

}  // namespace

void GltfDocument::validateVariants() {
  const auto root = model_.extensions.find(kVariants);
  if (root != model_.extensions.end()) {
    const tinygltf::Value& list = root->second.Get("variants");
    if (!list.IsArray()) error(fmt::format("{}: no variants list", kVariants));
    for (std::size_t v = 0; v < list.ArrayLen(); ++v) {
      const tinygltf::Value& name = list.Get(static_cast<int>(v)).Get("name");
      if (!name.IsString()) error(fmt::format("{}: variant {} has no name", kVariants, v));
      variants_.push_back(name.Get<std::string>());
    }
  }
  for (std::size_t m = 0; m < model_.meshes.size(); ++m)
    for (std::size_t p = 0; p < model_.meshes[m].primitives.size(); ++p) {
      const tinygltf::Primitive& prim = model_.meshes[m].primitives[p];
      const auto ext = prim.extensions.find(kVariants);
      if (ext == prim.extensions.end()) continue;
      const std::string where = primitiveLabel(static_cast<int>(m), p) + ": " + kVariants;
      const tinygltf::Value& mappings = ext->second.Get("mappings");
      if (!mappings.IsArray()) error(where + " without mappings");
      for (std::size_t k = 0; k < mappings.ArrayLen(); ++k) {
        const tinygltf::Value& mapping = mappings.Get(static_cast<int>(k));
        const std::string at = fmt::format("{} mapping {}", where, k);
        const std::optional<int> material = extensionIndex(mapping, "material", path_, at);
        if (!material) error(at + " without a material");
        if (!inRange(*material, model_.materials.size()))
          error(at + ": " + outOfRange("material", *material, model_.materials.size()));
        const tinygltf::Value& variants = mapping.Get("variants");
        if (!variants.IsArray()) error(at + " without variants");
        for (std::size_t i = 0; i < variants.ArrayLen(); ++i) {
          const tinygltf::Value& index = variants.Get(static_cast<int>(i));
          const int variant = index.IsInt() ? index.Get<int>() : -1;
          if (!index.IsInt() || !inRange(variant, variants_.size()))
            error(at + ": " +
                  (index.IsInt() ? outOfRange("variant", variant, variants_.size())
                                 : std::string("a variant is not an integer")));
          variantMaterials_[{static_cast<int>(m), p, variant}] = *material;
        }
      }
    }
  if (options_.variant.empty()) return;
  for (std::size_t v = 0; v < variants_.size(); ++v)
    if (variants_[v] == options_.variant) variant_ = static_cast<int>(v);
  if (variant_ < 0) {
    std::string names;
    for (const std::string& n : variants_) names += (names.empty() ? "'" : ", '") + n + "'";
    error(variants_.empty() ? fmt::format("has no material variants ({}), so none is named '{}'",
                                          kVariants, options_.variant)
                            : fmt::format("has no material variant named '{}' (it has {})",
                                          options_.variant, names));
  }
}

int GltfDocument::materialOf(int m, std::size_t p) const {
  const tinygltf::Primitive& prim = model_.meshes[static_cast<std::size_t>(m)].primitives[p];
  if (variant_ >= 0) {
    const auto found = variantMaterials_.find({m, p, variant_});
    if (found != variantMaterials_.end()) return found->second;
  }
  return prim.material;
}

}  // namespace ibl::gltf
