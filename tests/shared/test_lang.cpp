// The math of include/ibl/shared/ is written once, for the CPU (C++ with glm) and the GPU
// (GLSL): no shader and no library file may define a function of the same name again, except
// a C++ adapter whose body calls the shared one (an enum-typed front, say), and a shader's
// definition of a hook that a shared header only declares for GLSL (where the shader's data
// lives: charlieTableEntry reads a buffer). A second copy is how two paths drift apart while
// every test still passes.
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/helpers.hpp"
#include "support/text_file.hpp"

namespace {

namespace fs = std::filesystem;

using ibl::test::repositoryRoot;

using ibl::test::readText;

// The names that `pattern`'s first group captures in the shared headers.
std::set<std::string> sharedNamesMatching(const std::regex& pattern) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(repositoryRoot() / "include/ibl/shared")) {
    const std::string text = readText(e.path());
    for (std::sregex_iterator it(text.begin(), text.end(), pattern), end; it != end; ++it)
      names.insert((*it)[1].str());
  }
  return names;
}

// The names of the functions the shared headers define (`IBL_FN type name(`).
std::set<std::string> sharedFunctionNames() {
  return sharedNamesMatching(std::regex(R"(IBL_FN\s+\w+\s+(\w+)\s*\()"));
}

// The hooks: functions the shared headers declare without a body (`float name(int k);`), for
// the shaders to define.
std::set<std::string> shaderHooks() {
  return sharedNamesMatching(std::regex(R"((?:^|\n)\w+[ \t]+(\w+)\([^;{)]*\);)"));
}

// The body of the function whose opening brace is at `open`.
std::string bodyAt(const std::string& text, std::size_t open) {
  int depth = 0;
  for (std::size_t i = open; i < text.size(); ++i) {
    if (text[i] == '{') ++depth;
    if (text[i] == '}' && --depth == 0) return text.substr(open, i - open + 1);
  }
  return text.substr(open);
}

// A definition: a return type, a name, parameters without a body inside, then a body.
const std::regex& definitionPattern() {
  static const std::regex pattern(
      R"((?:^|\n)[ \t]*(?:inline\s+|static\s+|constexpr\s+)*[\w:<>]+[ \t]+(\w+)\s*\([^;{)]*\)\s*(?:const\s*)?\{)");
  return pattern;
}

struct Definition {
  std::string file, name;
};

// Definitions (a return type, the name, parameters, a body) of any of `names` in the shaders
// and the library's sources and headers outside include/ibl/shared.
std::vector<Definition> redefinitions(const std::set<std::string>& names) {
  std::vector<Definition> found;
  const std::set<std::string> hooks = shaderHooks();
  std::vector<fs::path> files;
  for (const char* dir : {"shaders", "src", "include/ibl"})
    for (const auto& e : fs::recursive_directory_iterator(repositoryRoot() / dir))
      if (e.is_regular_file() && e.path().parent_path().filename() != "shared") files.push_back(e);
  for (const auto& file : files) {
    const std::string text = readText(file);
    for (std::sregex_iterator it(text.begin(), text.end(), definitionPattern()), end; it != end;
         ++it) {
      const std::string name = (*it)[1].str();
      if (!names.count(name)) continue;
      const bool shader = fs::relative(file, repositoryRoot()).begin()->string() == "shaders";
      if (shader && hooks.count(name)) continue;
      const std::size_t open = static_cast<std::size_t>(it->position(0) + it->length(0) - 1);
      if (bodyAt(text, open).find("shared::" + name + "(") != std::string::npos) continue;
      found.push_back({fs::relative(file, repositoryRoot()).string(), name});
    }
  }
  return found;
}

TEST(SharedMath, TheSharedHeadersDefineTheShadingMath) {
  const auto names = sharedFunctionNames();
  // The pieces that were once written in several places, each now in ibl/shared/.
  for (const char* name : {"faceToDirection",
                           "directionToFace",
                           "faceAxis",
                           "texelDirection",
                           "ggxDistribution",
                           "smithGgxCorrelatedVisibility",
                           "ggxLobe",
                           "schlickWeight",
                           "disneyDiffuseRenormalized",
                           "sampleGgxVisibleNormal",
                           "tangentFrame",
                           "hammersley",
                           "shBasis",
                           "srgbToLinear",
                           "toneMap",
                           "splitSumLookup",
                           "splitSumRadiance",
                           "specularLodForRoughness",
                           "applyNormalMap",
                           "dfgIntegrand"})
    EXPECT_TRUE(names.count(name)) << name << " is not defined in include/ibl/shared";
}

TEST(SharedMath, NoSecondDefinitionInShadersOrSources) {
  const auto names = sharedFunctionNames();
  ASSERT_GT(names.size(), 30u);
  EXPECT_TRUE(shaderHooks().count("charlieTableEntry"));
  for (const auto& d : redefinitions(names))
    ADD_FAILURE() << d.file << " defines " << d.name << " again; include ibl/shared instead";
}

// The scan itself finds a second definition (a GLSL copy, a C++ copy) and lets an adapter
// that forwards to the shared function pass.
TEST(SharedMath, TheScanFindsCopies) {
  const auto defines = [](const std::string& text) {
    std::smatch m;
    return std::regex_search(text, m, definitionPattern()) ? m[1].str() : std::string();
  };
  EXPECT_EQ(defines("float schlickWeight(float VoH) {\n  return 0.0;\n}"), "schlickWeight");
  EXPECT_EQ(defines("vec3 faceToDirection(int face, float sc, float tc) {"), "faceToDirection");
  EXPECT_EQ(defines("inline glm::vec3 toneMap(glm::vec3 c, ToneMap curve) {"), "toneMap");
  EXPECT_EQ(defines("  return schlickWeight(x);"), "");
  EXPECT_EQ(defines("float schlickWeight(float VoH);"), "");
  const std::string adapter = "{\n  return shared::toneMap(c, 1);\n}";
  EXPECT_NE(bodyAt(adapter, 0).find("shared::toneMap("), std::string::npos);
}

}  // namespace
