// The viewer's descriptor bindings are numbered once (include/ibl/shared/view_bindings.h), and
// the shaders use the names: each number appears once, from 0 up, as many as the C++
// enumerations count; frame.glsl and material.glsl declare each name exactly once (and the
// material's factors after its textures); no shader
// that includes them binds set 0 or 1 by a literal number.
#include <filesystem>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ibl/io/file_io.hpp"
#include "ibl/shared/view_bindings.h"
#include "support/helpers.hpp"

using namespace ibl;

namespace {

namespace fs = std::filesystem;

using ibl::test::repositoryRoot;

std::string textOf(const fs::path& path) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  return {bytes.begin(), bytes.end()};
}

// The header's IBL_<macro>(Name, number) lines, by name.
std::map<std::string, int> declaredNumbers(const std::string& macro) {
  const std::string text = textOf(repositoryRoot() / "include/ibl/shared/view_bindings.h");
  const std::regex line("\\n" + macro + R"(\((\w+), (\d+)\))");
  std::map<std::string, int> numbers;
  for (std::sregex_iterator it(text.begin(), text.end(), line), end; it != end; ++it)
    numbers[(*it)[1].str()] = std::stoi((*it)[2].str());
  return numbers;
}

// How often `shader` declares `layout(... set = <set>, binding = <prefix><name>)`, by name.
std::map<std::string, int> shaderUses(const std::string& shader, int set,
                                      const std::string& prefix) {
  const std::string text = textOf(repositoryRoot() / "shaders/view" / shader);
  const std::regex use("set = " + std::to_string(set) + ", binding = " + prefix + R"((\w+)\))");
  std::map<std::string, int> uses;
  for (std::sregex_iterator it(text.begin(), text.end(), use), end; it != end; ++it)
    uses[(*it)[1].str()] += 1;
  return uses;
}

// Checks that `numbers` are 0, 1, ... count - 1, each once.
void expectZeroToCount(const std::map<std::string, int>& numbers, unsigned count) {
  EXPECT_EQ(numbers.size(), count);
  std::vector<int> seen(count, 0);
  for (const auto& [name, number] : numbers) {
    ASSERT_GE(number, 0) << name;
    ASSERT_LT(number, static_cast<int>(count)) << name;
    seen[static_cast<std::size_t>(number)] += 1;
  }
  for (unsigned b = 0; b < count; ++b) EXPECT_EQ(seen[b], 1) << "binding " << b;
}

}  // namespace

TEST(ViewBindings, EachNumberOnceFromZero) {
  expectZeroToCount(declaredNumbers("IBL_FRAME_BINDING"),
                    static_cast<unsigned>(shared::FrameBinding::Count));
  expectZeroToCount(declaredNumbers("IBL_MATERIAL_BINDING"),
                    static_cast<unsigned>(shared::MaterialBinding::Count));
  EXPECT_EQ(static_cast<unsigned>(shared::FrameBinding::LightClusters), 16u);
  EXPECT_EQ(static_cast<unsigned>(shared::MaterialBinding::Emissive), 4u);
}

TEST(ViewBindings, ShadersDeclareEachNameOnce) {
  const std::map<std::string, int> frame = shaderUses("frame.glsl", 0, "kFrame");
  const std::map<std::string, int> material = shaderUses("material.glsl", 1, "kMaterial");
  for (const auto& [name, number] : declaredNumbers("IBL_FRAME_BINDING"))
    EXPECT_EQ(frame.count(name) ? frame.at(name) : 0, 1) << name << " (" << number << ")";
  for (const auto& [name, number] : declaredNumbers("IBL_MATERIAL_BINDING"))
    EXPECT_EQ(material.count(name) ? material.at(name) : 0, 1) << name << " (" << number << ")";
  EXPECT_EQ(frame.size(), static_cast<std::size_t>(shared::FrameBinding::Count));
  // The textures, then the material's factors (kMaterialFactors) right after them.
  EXPECT_EQ(material.count("Factors") ? material.at("Factors") : 0, 1);
  EXPECT_EQ(shared::kMaterialFactors, static_cast<int>(shared::MaterialBinding::Count));
  EXPECT_EQ(material.size(), static_cast<std::size_t>(shared::MaterialBinding::Count) + 1);
  // No literal numbers in the sets the names cover, in the shaders of the frame set (the
  // window's tone map and the bloom have sets of their own).
  const std::regex literal(R"(set = [01], binding = \d)");
  for (const auto& e : fs::directory_iterator(repositoryRoot() / "shaders/view")) {
    const std::string text = textOf(e.path());
    const std::string name = e.path().filename().string();
    const bool frameSet = name == "frame.glsl" || name == "material.glsl" ||
                          text.find("view/frame.glsl") != std::string::npos ||
                          text.find("view/material.glsl") != std::string::npos;
    if (!frameSet) continue;
    EXPECT_FALSE(std::regex_search(text, literal)) << e.path();
  }
}
