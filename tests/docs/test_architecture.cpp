// docs/architecture.md's naming rule for tests: a source src/<part>/x.cpp is tested in
// tests/<part>/test_x.cpp (src/render/gltf/x.cpp in tests/render/gltf/test_x.cpp), and a header
// of the math shared with the shaders, include/ibl/shared/x.h, in tests/shared/test_x.cpp, or,
// where the library has a C++ face of the same name (shared/sh.h and src/math/sh.cpp), in that
// face's test file. A file that has no test of its name is listed below with the reason; the
// list fails too when one of its files is gone or has its test file now, so that it cannot rot.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "support/text_file.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kSource = IBL_SOURCE_DIR;

struct Exception {
  std::string_view path;    // relative to the repository's root
  std::string_view reason;  // why it has no test file of its name
};

// The sources and shared headers without a test file of their name. Keep it short: a source
// gets its file (tests moved there, or a small test against an independent computation) rather
// than a line here.
constexpr Exception kExceptions[] = {
    // Vulkan objects only (the set, its pool and stand-ins); the layout it builds is
    // frame_layout.cpp's, tested in tests/gpu/test_frame_layout.cpp, and the set in use by every
    // Viewer test.
    {"src/gpu/frame_set.cpp",
     "the frame's descriptor set, tested as tests/gpu/test_frame_layout.cpp"},
    // The loader's steps that turn a validated document into a Scene: they have no inputs of
    // their own to test apart from a whole glTF file, so the loader's tests (tests/render/gltf/
    // test_gltf.cpp, test_load_geometry.cpp) and the renderers' (LightRender.GltfPunctual...,
    // SheenRender.GltfSheen...) drive them; `summary` is what `ibl info` prints (tests/cli/).
    {"src/render/gltf/load_lights.cpp", "KHR_lights_punctual, tested through the loader's tests"},
    {"src/render/gltf/load_materials.cpp", "materials, tested through the loader's tests"},
    {"src/render/gltf/load_scene.cpp", "scene assembly, tested through the loader's tests"},
    {"src/render/gltf/summary.cpp", "the summary `ibl info` prints, tested by tests/cli/"},
};

// The files of `dir` (under `root`, relative to it) whose name ends in `extension`, in every
// subfolder when `recursive`, sorted.
std::vector<fs::path> filesUnder(const fs::path& root, const fs::path& dir,
                                 std::string_view extension, bool recursive) {
  std::vector<fs::path> files;
  const auto add = [&](const fs::directory_entry& e) {
    if (e.is_regular_file() && e.path().extension() == extension)
      files.push_back(e.path().lexically_relative(root));
  };
  if (recursive) {
    for (const auto& e : fs::recursive_directory_iterator(root / dir)) add(e);
  } else {
    for (const auto& e : fs::directory_iterator(root / dir)) add(e);
  }
  std::sort(files.begin(), files.end());
  return files;
}

// The test file of a source src/<part>/x.cpp, tests/<part>/test_x.cpp, or of a shared header
// include/ibl/shared/x.h, tests/shared/test_x.cpp (relative paths).
fs::path testFileOf(const fs::path& file) {
  const fs::path name = "test_" + file.stem().string() + ".cpp";
  if (*file.begin() == "src") return "tests" / file.parent_path().lexically_relative("src") / name;
  return "tests/shared" / name;
}

// The sources (src/**/*.cpp) and shared headers (include/ibl/shared/*.h) of the tree at `root`
// that have no test file of their name, a header none of its C++ face either (the source of
// the same name, if there is one). Generated sources live in the build folder: not walked.
std::vector<fs::path> filesWithoutTests(const fs::path& root) {
  const auto tested = [&](const fs::path& f) { return fs::exists(root / testFileOf(f)); };
  const std::vector<fs::path> sources = filesUnder(root, "src", ".cpp", true);
  std::vector<fs::path> missing;
  for (const fs::path& s : sources)
    if (!tested(s)) missing.push_back(s);
  for (const fs::path& h : filesUnder(root, "include/ibl/shared", ".h", false)) {
    const bool faceTested = std::any_of(sources.begin(), sources.end(), [&](const fs::path& s) {
      return s.stem() == h.stem() && tested(s);
    });
    if (!tested(h) && !faceTested) missing.push_back(h);
  }
  return missing;
}

using ibl::test::readText;

// The first group of `pattern`'s first match in the repository's `file`; "" without a match.
std::string firstMatch(const fs::path& file, const std::regex& pattern) {
  const std::string text = readText(kSource / file);
  std::smatch m;
  return std::regex_search(text, m, pattern) ? m[1].str() : std::string();
}

// The suites scripts/test.sh runs under ThreadSanitizer (its ctest -R '^(A|B|...)\.').
std::set<std::string> threadSanitizerSuites() {
  std::stringstream list(firstMatch("scripts/test.sh", std::regex(R"(-R '\^\(([\w|]+)\)\\\.')")));
  std::set<std::string> suites;
  for (std::string suite; std::getline(list, suite, '|');) suites.insert(suite);
  return suites;
}

// The files of tests/CMakeLists.txt's IBL_PARALLEL_TESTS, which a ThreadSanitizer build compiles.
std::set<std::string> parallelTestFiles() {
  std::stringstream list(
      firstMatch("tests/CMakeLists.txt", std::regex(R"(set\(IBL_PARALLEL_TESTS([^)]*)\))")));
  return {std::istream_iterator<std::string>(list), std::istream_iterator<std::string>()};
}

// A scratch tree of empty files, removed by the destructor.
class ScratchTree {
 public:
  explicit ScratchTree(const std::vector<fs::path>& files)
      : root_(fs::temp_directory_path() / ("ibl_architecture_" + std::to_string(::getpid()))) {
    fs::remove_all(root_);
    for (const fs::path& f : files) {
      fs::create_directories((root_ / f).parent_path());
      std::ofstream(root_ / f) << "";
    }
  }
  ~ScratchTree() { fs::remove_all(root_); }
  const fs::path& root() const { return root_; }

 private:
  fs::path root_;
};

}  // namespace

TEST(Architecture, EverySourceHasATestFileOfItsName) {
  const std::vector<fs::path> missing = filesWithoutTests(kSource);
  const auto excepted = [](const fs::path& f) {
    return std::any_of(std::begin(kExceptions), std::end(kExceptions),
                       [&](const Exception& e) { return fs::path(e.path) == f; });
  };
  for (const fs::path& f : missing)
    if (!excepted(f))
      ADD_FAILURE() << f.string() << " has no test file " << testFileOf(f).string()
                    << " (docs/architecture.md): write it, or add the file to kExceptions in "
                       "tests/docs/test_architecture.cpp with the reason";
  for (const Exception& e : kExceptions) {
    EXPECT_FALSE(e.reason.empty()) << e.path;
    if (!fs::exists(kSource / e.path))
      ADD_FAILURE() << "kExceptions names " << e.path << ", which no longer exists";
    else if (std::find(missing.begin(), missing.end(), fs::path(e.path)) == missing.end())
      ADD_FAILURE() << e.path << " has its test file now: remove it from kExceptions";
  }
}

// The walk itself, over a tree made here: a source without its test file, one in a subfolder
// with its file, a shared header tested through its C++ face, one tested in tests/shared/ and one
// tested nowhere; files of other kinds are not walked.
TEST(Architecture, TheWalkFindsFilesWithoutTests) {
  const ScratchTree tree({"src/io/tested.cpp", "tests/io/test_tested.cpp", "src/io/untested.cpp",
                          "src/render/gltf/images.cpp", "tests/render/gltf/test_images.cpp",
                          "src/render/table.inc", "src/env/default.cpp.in",
                          "include/ibl/shared/tested.h", "include/ibl/shared/alone.h",
                          "tests/shared/test_alone.cpp", "include/ibl/shared/untested.h",
                          "include/ibl/shared/notes.md"});
  EXPECT_EQ(filesWithoutTests(tree.root()),
            (std::vector<fs::path>{"src/io/untested.cpp", "include/ibl/shared/untested.h"}));
  EXPECT_EQ(testFileOf("src/render/gltf/images.cpp"),
            fs::path("tests/render/gltf/test_images.cpp"));
  EXPECT_EQ(testFileOf("include/ibl/shared/sh.h"), fs::path("tests/shared/test_sh.cpp"));
}

// A ThreadSanitizer build compiles only IBL_PARALLEL_TESTS: a test file of a suite the script
// runs there must be in that list, or ThreadSanitizer never sees its tests.
TEST(Architecture, ThreadSanitizersSuitesAreInItsBuild) {
  const std::set<std::string> suites = threadSanitizerSuites(), files = parallelTestFiles();
  ASSERT_GT(suites.size(), 10u) << "scripts/test.sh's ThreadSanitizer -R not found";
  ASSERT_GT(files.size(), 10u) << "tests/CMakeLists.txt's IBL_PARALLEL_TESTS not found";
  const std::regex test(R"((?:^|\n)TEST(?:_F|_P)?\((\w+),)");
  for (const fs::path& file : filesUnder(kSource, "tests", ".cpp", true)) {
    const std::string text = readText(kSource / file);
    for (std::sregex_iterator it(text.begin(), text.end(), test), end; it != end; ++it) {
      const std::string relative = file.lexically_relative("tests").string();
      if (suites.count((*it)[1].str()) && !files.count(relative)) {
        ADD_FAILURE() << file.string() << " holds tests of " << (*it)[1].str()
                      << ", which ThreadSanitizer runs: add it to IBL_PARALLEL_TESTS";
        break;
      }
    }
  }
}
