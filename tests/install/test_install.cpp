// The installed ibl as its users meet it (docs/install.md): `cmake --install` into a scratch
// prefix, the command run from another folder, the example program built against the installed
// CMake package and through pkg-config, the source tree added with add_subdirectory, and the
// Debian packages unpacked with dpkg -x.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_command.hpp"

namespace fs = std::filesystem;
using ibl::test::runCommand;

namespace {

const fs::path kSource = IBL_SOURCE_DIR;
const fs::path kBuild = IBL_BUILD_DIR;
const std::string kVersion = IBL_VERSION;                // the project's version (CMake)
const std::string kSoname = "libibl.so." IBL_SOVERSION;  // major.minor before 1.0

std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

// A scratch folder for one test, removed after it.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "ibl-install-XXXXXX").string();
    path_ = mkdtemp(pattern.data());
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// Installs the build folder into `prefix`; fails the test if cmake does.
void install(const fs::path& prefix) {
  const auto r = runCommand("cmake --install " + quoted(kBuild) + " --prefix " + quoted(prefix));
  ASSERT_EQ(r.status, 0) << r.output;
}

// A clean environment: no LD_LIBRARY_PATH, no PYTHONPATH, only the system's PATH.
const std::string kCleanEnv = "env -i PATH=/usr/bin:/bin HOME=/tmp ";

// The irradiance the example prints and the exact value it states; checked against the closed
// form here too: pi (1 + 0.5 * 2/3) for its sky L = 1 + 0.5 y.
void expectExampleOutput(const std::string& output) {
  std::smatch m;
  ASSERT_TRUE(std::regex_search(output, m,
                                std::regex(R"(ibl (\S+): irradiance on an upward plane = (\S+))")))
      << output;
  EXPECT_EQ(m[1].str(), kVersion);
  const double exact = std::numbers::pi * (1.0 + 0.5 * 2.0 / 3.0);
  EXPECT_NEAR(std::stod(m[2].str()), exact, 0.005 * exact) << output;
  ASSERT_TRUE(std::regex_search(output, m, std::regex(R"(shaded radiance = (\S+) (\S+) (\S+))")))
      << output;
  // A white dielectric cannot send back more than its irradiance over pi (4/3 here), and a
  // rough white surface under this sky sends back most of it.
  for (int c = 1; c <= 3; ++c) {
    const double radiance = std::stod(m[c].str());
    EXPECT_GT(radiance, 0.7) << output;
    EXPECT_LE(radiance, 4.0 / 3.0 * 1.01) << output;
  }
}

#ifdef IBL_PYTHON
// The Python module in `sitePackages` imports in a clean environment, from there, and finds the
// library installed beside it (its RUNPATH), not the build folder's.
void expectPythonModuleImports(const fs::path& sitePackages) {
  const auto r =
      runCommand(kCleanEnv + "PYTHONPATH=" + quoted(sitePackages) + " " + IBL_PYTHON +
                 " -c 'import ibl, os; print(ibl.__version__, os.path.dirname(ibl.__file__)); "
                 "print(open(\"/proc/self/maps\").read())'");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.substr(0, r.output.find('\n')), kVersion + " " + sitePackages.string());
  const fs::path lib = sitePackages.parent_path().parent_path() / ("libibl.so." + kVersion);
  EXPECT_NE(r.output.find(fs::weakly_canonical(lib).string()), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(kBuild.string()), std::string::npos) << r.output;
}
#endif

}  // namespace

TEST(Install, PutsEachFileWhereThePrefixLayoutSays) {
  ScratchDir scratch;
  const fs::path p = scratch.path() / "prefix";
  install(p);
  for (const char* file :
       {"bin/ibl", "include/ibl/bake/bake.hpp", "include/ibl/core/version.hpp",
        "include/ibl/shared/brdf.h", "lib/cmake/ibl/iblConfig.cmake",
        "lib/cmake/ibl/iblConfigVersion.cmake", "lib/cmake/ibl/iblTargets.cmake",
        "lib/pkgconfig/ibl.pc", "share/man/man1/ibl.1.gz", "share/man/man1/ibl-bake.1.gz",
        "share/bash-completion/completions/ibl", "share/zsh/site-functions/_ibl",
        "share/doc/ibl/copyright", "share/doc/ibl/changelog.gz"})
    EXPECT_TRUE(fs::is_regular_file(p / file)) << file;
  // The versioned library, its SONAME link and the development link.
  const fs::path real = p / "lib" / ("libibl.so." + kVersion);
  EXPECT_TRUE(fs::is_regular_file(real) && !fs::is_symlink(real));
  EXPECT_EQ(fs::read_symlink(p / "lib" / kSoname), real.filename());
  EXPECT_EQ(fs::read_symlink(p / "lib/libibl.so"), fs::path(kSoname));
  const auto soname = runCommand("readelf -d " + quoted(real));
  EXPECT_NE(soname.output.find("Library soname: [" + kSoname + "]"), std::string::npos)
      << soname.output;
  // Nothing of the source tree or the build folder is needed: the command finds its library
  // next to itself.
  const auto runpath = runCommand("readelf -d " + quoted(p / "bin/ibl"));
  EXPECT_NE(runpath.output.find("[$ORIGIN/../lib]"), std::string::npos) << runpath.output;
  EXPECT_EQ(runpath.output.find(kBuild.string()), std::string::npos) << runpath.output;
#ifdef IBL_PYTHON
  expectPythonModuleImports(p / "lib/python3/dist-packages");
#endif
}

TEST(Install, CommandRunsFromAnotherFolder) {
  ScratchDir scratch;
  const fs::path p = scratch.path() / "prefix";
  install(p);
  const std::string cd = "cd " + quoted(scratch.path()) + " && " + kCleanEnv;
  const auto version = runCommand(cd + quoted(p / "bin/ibl") + " --version");
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.output, "ibl " + kVersion + "\n");
  // The bundled environment and the shaders are inside the library: a bake works anywhere.
  const auto bake = runCommand(cd + quoted(p / "bin/ibl") +
                               " bake -o out --size 16 --irradiance-size 8 --dfg-size 16 --quiet");
  ASSERT_EQ(bake.status, 0) << bake.output;
  EXPECT_TRUE(fs::is_regular_file(scratch.path() / "out/manifest.json"));
  // The library the command loads is the installed one.
  const auto ldd = runCommand(kCleanEnv + "ldd " + quoted(p / "bin/ibl"));
  EXPECT_NE(ldd.output.find(kSoname + " => " + (p / "bin/../lib" / kSoname).string()),
            std::string::npos)
      << ldd.output;
}

TEST(Install, ExampleBuildsAgainstTheCMakePackage) {
  ScratchDir scratch;
  const fs::path p = scratch.path() / "prefix", b = scratch.path() / "build";
  install(p);
  const auto configure =
      runCommand(kCleanEnv + "cmake -S " + quoted(kSource / "examples") + " -B " + quoted(b) +
                 " -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=" + quoted(p));
  ASSERT_EQ(configure.status, 0) << configure.output;
  // The package found is the installed one, with its version file consulted.
  std::ifstream cache(b / "CMakeCache.txt");
  const std::string text((std::istreambuf_iterator<char>(cache)), {});
  EXPECT_NE(text.find("ibl_DIR:PATH=" + (p / "lib/cmake/ibl").string()), std::string::npos);
  const auto build = runCommand(kCleanEnv + "cmake --build " + quoted(b));
  ASSERT_EQ(build.status, 0) << build.output;
  const auto run = runCommand(kCleanEnv + quoted(b / "bake_from_memory"));
  ASSERT_EQ(run.status, 0) << run.output;
  expectExampleOutput(run.output);
}

TEST(Install, CMakePackageRefusesAnotherMinorVersion) {
  ScratchDir scratch;
  const fs::path p = scratch.path() / "prefix";
  install(p);
  // Before 1.0 a minor version may break the API: asking for the next one must fail.
  const fs::path project = scratch.path() / "consumer";
  fs::create_directories(project);
  const int major = std::stoi(kVersion), minor = std::stoi(kVersion.substr(kVersion.find('.') + 1));
  std::ofstream(project / "CMakeLists.txt")
      << "cmake_minimum_required(VERSION 3.25)\nproject(consumer CXX)\nfind_package(ibl " << major
      << "." << minor + 1 << " CONFIG REQUIRED)\n";
  const auto r = runCommand(kCleanEnv + "cmake -S " + quoted(project) + " -B " +
                            quoted(scratch.path() / "build") + " -DCMAKE_PREFIX_PATH=" + quoted(p));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("version: " + kVersion), std::string::npos) << r.output;
}

TEST(Install, ExampleBuildsThroughPkgConfig) {
  ScratchDir scratch;
  const fs::path p = scratch.path() / "prefix";
  install(p);
  const std::string pkg = "PKG_CONFIG_PATH=" + quoted(p / "lib/pkgconfig") + " ";
  const auto flags = runCommand(kCleanEnv + pkg + "pkg-config --cflags --libs ibl");
  ASSERT_EQ(flags.status, 0) << flags.output;
  EXPECT_NE(flags.output.find("-libl"), std::string::npos) << flags.output;
  const fs::path exe = scratch.path() / "bake_from_memory";
  const auto build =
      runCommand(kCleanEnv + "g++ -std=c++20 -O1 " +
                 quoted(kSource / "examples/bake_from_memory.cpp") + " -o " + quoted(exe) + " $(" +
                 pkg + "pkg-config --cflags --libs ibl)" + " -Wl,-rpath," + quoted(p / "lib"));
  ASSERT_EQ(build.status, 0) << build.output;
  const auto run = runCommand(kCleanEnv + quoted(exe));
  ASSERT_EQ(run.status, 0) << run.output;
  expectExampleOutput(run.output);
}

TEST(Install, AddSubdirectoryGivesTheSameTarget) {
  // A project that adds ibl's source tree: ibl::ibl exists without find_package, and the
  // example's build depends on the library's (configured, not built: that is the main build).
  ScratchDir scratch;
  const fs::path project = scratch.path() / "consumer", b = scratch.path() / "build";
  fs::create_directories(project);
  std::ofstream(project / "CMakeLists.txt")
      << "cmake_minimum_required(VERSION 3.25)\nproject(consumer CXX)\n"
      << "add_subdirectory(\"" << kSource.string() << "\" ibl)\n"
      << "if(IBL_BUILD_TESTS OR IBL_BUILD_PYTHON OR IBL_INSTALL)\n"
      << "  message(FATAL_ERROR \"tests, Python or install rules on in a subproject\")\n"
      << "endif()\n"
      << "add_subdirectory(\"" << (kSource / "examples").string() << "\" examples)\n";
  const auto configure = runCommand("cmake -S " + quoted(project) + " -B " + quoted(b) +
                                    " -G Ninja -DCMAKE_BUILD_TYPE=Release");
  ASSERT_EQ(configure.status, 0) << configure.output;
  // Every command that builds the example: the library's sources compiled, then the example
  // linked against the library.
  const auto plan = runCommand("ninja -C " + quoted(b) + " -t commands bake_from_memory");
  ASSERT_EQ(plan.status, 0) << plan.output;
  EXPECT_NE(plan.output.find("-c " + (kSource / "src/bake/bake.cpp").string()), std::string::npos)
      << plan.output;
  EXPECT_TRUE(
      std::regex_search(plan.output, std::regex("-o examples/bake_from_memory .*ibl/libibl\\.so")))
      << plan.output;
}

// The Debian packages cpack builds from the build folder, in a scratch folder: their names
// (libibl0.1 after the library's SONAME, ibl, ibl-dev, python3-ibl when the module is built) and
// files.
struct DebianPackages {
  ScratchDir scratch;
  fs::path out = scratch.path() / "packages";
  std::vector<std::string> names{kLibraryPackage, "ibl", "ibl-dev"};
  std::string suffix;  // _<version>_<arch>.deb
  std::string cpackOutput;
  int cpackStatus = 0;

  static inline const std::string kLibraryPackage = "libibl" IBL_SOVERSION;

  DebianPackages() {
#ifdef IBL_PYTHON
    names.push_back("python3-ibl");
#endif
    const auto cpack = runCommand("cpack -G DEB --config " + quoted(kBuild / "CPackConfig.cmake") +
                                  " -B " + quoted(out));
    cpackStatus = cpack.status;
    cpackOutput = cpack.output;
    const std::string arch = runCommand("dpkg --print-architecture").output;
    suffix = "_" + kVersion + "_" + arch.substr(0, arch.find('\n')) + ".deb";
  }
  fs::path deb(const std::string& name) const {
    return out / (name + suffix);
  }
  std::string field(const std::string& name, const std::string& field) const {
    return runCommand("dpkg-deb -f " + quoted(deb(name)) + " " + field).output;
  }
};

// Debian's own checker (scripts/setup.sh installs it) on the packages: no error; the warnings
// it still gives are listed and justified in docs/install.md.
void expectLintianFindsNoError(const DebianPackages& packages) {
  std::string debs;
  for (const std::string& name : packages.names) debs += " " + quoted(packages.deb(name));
  const auto lintian = runCommand("lintian --tag-display-limit 0" + debs);
  std::string errors;
  std::istringstream lines(lintian.output);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("E: ", 0) == 0) errors += line + "\n";
  EXPECT_EQ(errors, "") << lintian.output;
  // Its status: 0 when it ran and found no error (1 for errors, 2 when it failed to run, 127
  // when it is not installed).
  EXPECT_EQ(lintian.status, 0) << lintian.output;
}

TEST(Install, DebianPackagesUnpackAndRun) {
  const DebianPackages packages;
  ASSERT_EQ(packages.cpackStatus, 0) << packages.cpackOutput;
  expectLintianFindsNoError(packages);  // here, not in a test of its own: one cpack for both
  const fs::path root = packages.scratch.path() / "root";
  for (const std::string& name : packages.names) {
    ASSERT_TRUE(fs::is_regular_file(packages.deb(name))) << packages.deb(name) << "\n"
                                                         << packages.cpackOutput;
    const auto x = runCommand("dpkg -x " + quoted(packages.deb(name)) + " " + quoted(root));
    ASSERT_EQ(x.status, 0) << x.output;
    // Debian's policy: each package's machine-readable copyright file and changelog.
    const fs::path doc = root / "usr/share/doc" / name;
    EXPECT_TRUE(fs::is_regular_file(doc / "changelog.gz")) << name;
    std::ifstream copyright(doc / "copyright");
    std::string first;
    std::getline(copyright, first);
    EXPECT_EQ(first, "Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/")
        << name;
  }
  // The library alone in the package named after its SONAME, with the shlibs file that makes
  // a program linking it depend on it.
  const std::string lib = DebianPackages::kLibraryPackage;
  const auto contents = runCommand("dpkg-deb -c " + quoted(packages.deb(lib)));
  EXPECT_NE(contents.output.find("./usr/lib/" + kSoname + " -> libibl.so." + kVersion),
            std::string::npos)
      << contents.output;
  EXPECT_NE(contents.output.find("./usr/lib/libibl.so." + kVersion + "\n"), std::string::npos)
      << contents.output;
  EXPECT_EQ(contents.output.find("usr/bin"), std::string::npos) << contents.output;
  EXPECT_EQ(contents.output.find("./usr/lib/libibl.so "), std::string::npos) << contents.output;
  const auto shlibs =
      runCommand("dpkg-deb --ctrl-tarfile " + quoted(packages.deb(lib)) + " | tar -xO ./shlibs");
  EXPECT_EQ(shlibs.output, "libibl " IBL_SOVERSION " " + lib + " (= " + kVersion + ")\n");
  // Dependencies computed from the shared libraries the command and the library link (oneTBB,
  // Vulkan, OpenEXR, the C++ runtime), not written by hand; the command's on the library's
  // package of its version.
  const std::string libDepends = packages.field(lib, "Depends");
  for (const char* needed : {"libtbb12", "libvulkan1", "libopenexr-3-1-30", "libstdc++6"})
    EXPECT_NE(libDepends.find(needed), std::string::npos) << needed << ": " << libDepends;
  const std::string exact = lib + " (= " + kVersion + ")";
  for (const char* name : {"ibl", "ibl-dev"})
    EXPECT_NE(packages.field(name, "Depends").find(exact), std::string::npos)
        << name << ": " << packages.field(name, "Depends");
  EXPECT_TRUE(fs::is_regular_file(root / "usr/lib/cmake/ibl/iblConfig.cmake"));
  EXPECT_TRUE(fs::is_regular_file(root / "usr/include/ibl/render/renderer.hpp"));
  EXPECT_EQ(fs::read_symlink(root / "usr/lib/libibl.so"), fs::path(kSoname));
  // Manual pages compressed, as Debian's policy asks: gzip without a name or a time stamp.
  const fs::path page = root / "usr/share/man/man1/ibl-render.1.gz";
  ASSERT_TRUE(fs::is_regular_file(page));
  std::ifstream gz(page, std::ios::binary);
  unsigned char header[8] = {};
  gz.read(reinterpret_cast<char*>(header), sizeof header);
  EXPECT_EQ(header[0], 0x1f);
  EXPECT_EQ(header[1], 0x8b);
  EXPECT_EQ(header[3] & 0x08, 0) << "a file name in the gzip header";
  EXPECT_EQ(header[4] | header[5] | header[6] | header[7], 0) << "a time stamp in the gzip header";
  const auto man = runCommand("zcat " + quoted(page) + " | grep -m1 '^\\.TH '");
  EXPECT_NE(man.output.find(".TH"), std::string::npos) << man.output;
  // Where Debian's bash-completion and zsh look for a package's completions.
  EXPECT_TRUE(fs::is_regular_file(root / "usr/share/bash-completion/completions/ibl"));
  EXPECT_TRUE(fs::is_regular_file(root / "usr/share/zsh/vendor-completions/_ibl"));
  const auto version = runCommand("cd " + quoted(packages.scratch.path()) + " && " + kCleanEnv +
                                  quoted(root / "usr/bin/ibl") + " --version");
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.output, "ibl " + kVersion + "\n");
#ifdef IBL_PYTHON
  // The module is built for one Python ABI (its file name says which): the package says so.
  const std::string pythonDepends = packages.field("python3-ibl", "Depends");
  const auto abi =
      runCommand(std::string(IBL_PYTHON) +
                 " -c 'import sys; v = sys.version_info; "
                 "print(f\"python3 (>= {v[0]}.{v[1]}), python3 (<< {v[0]}.{v[1] + 1})\")'");
  EXPECT_NE(pythonDepends.find(abi.output.substr(0, abi.output.find('\n'))), std::string::npos)
      << pythonDepends << " / " << abi.output;
  EXPECT_NE(pythonDepends.find("python3-numpy"), std::string::npos);
  EXPECT_NE(pythonDepends.find(exact), std::string::npos) << pythonDepends;
  expectPythonModuleImports(root / "usr/lib/python3/dist-packages");
#endif
}

TEST(Install, EveryInstalledHeaderSaysWhetherItIsStable) {
  // Its second line (the first of a shared C++/GLSL header): "// API: stable", or
  // "// API: internal (<why>)", docs/install.md#stable-and-internal-headers.
  ScratchDir scratch;
  const fs::path p = scratch.path() / "prefix";
  install(p);
  const std::regex marker(R"(// API: (stable|internal \(.+\)))");
  int headers = 0, stable = 0;
  for (const auto& e : fs::recursive_directory_iterator(p / "include/ibl")) {
    if (!e.is_regular_file()) continue;
    ++headers;
    std::ifstream in(e.path());
    std::string line;
    int found = 0;
    for (int n = 0; n < 2 && std::getline(in, line); ++n) {
      std::smatch m;
      if (std::regex_match(line, m, marker)) {
        ++found;
        stable += m[1] == "stable";
      }
    }
    EXPECT_EQ(found, 1) << e.path();
  }
  EXPECT_GT(headers, 60);
  EXPECT_GE(stable, 20);  // the embedding API: errors, images, environments, bake, render...
  EXPECT_LT(stable, headers / 2);
}
