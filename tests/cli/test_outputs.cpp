// Commands that write several files write all of them or none, a bake into an existing
// directory replaces exactly its own files, and readers of a bake check it against its manifest.
#include <algorithm>
#include <csignal>
#include <fstream>
#include <map>
#include <random>
#include <thread>

#include <fmt/format.h>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;
namespace fs = std::filesystem;

namespace {

// Runs `ibl args` with files limited to `kib` KiB (RLIMIT_FSIZE): a write past it fails as on
// a full disk (SIGXFSZ ignored, so the write returns an error instead of killing the process).
CliRun runIblWithFileLimit(const std::string& args, int kib) {
  return runCommand("trap '' XFSZ; ulimit -f " + std::to_string(kib) + "; " + std::string(IBL_CLI) +
                    " " + args);
}

std::map<std::string, std::vector<std::uint8_t>> filesIn(const fs::path& dir) {
  std::map<std::string, std::vector<std::uint8_t>> files;
  for (const auto& e : fs::directory_iterator(dir))
    files[e.path().filename().string()] = readFileBytes(e.path());
  return files;
}

const std::string kQuietBake = " --dfg-size 16 --dfg-samples 64 --quiet";

}  // namespace

TEST(Outputs, WriteFilesTogetherWritesAllOrNone) {
  TempDir dir;
  writeFileAtomic(dir / "a.bin", std::vector<std::uint8_t>{1, 2, 3});
  fs::create_directories(dir / "d.bin" / "inside");  // the fourth destination is a directory
  std::vector<EncodedFile> files;
  for (const char* name : {"a.bin", "b.bin", "c.bin", "d.bin", "e.bin"})
    files.push_back({dir / name, std::vector<std::uint8_t>(100, 7)});
  try {
    writeFilesTogether(files);
    FAIL() << "writing onto a directory succeeded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("d.bin: is a directory"), std::string::npos) << e.what();
  }
  EXPECT_EQ(readFileBytes(dir / "a.bin"), (std::vector<std::uint8_t>{1, 2, 3}));  // kept
  for (const char* name : {"b.bin", "c.bin", "e.bin"}) EXPECT_FALSE(fs::exists(dir / name));
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 2);  // a.bin and the directory: no temporary file left
  files.erase(files.begin() + 3);
  writeFilesTogether(files);
  for (const auto& f : files) EXPECT_EQ(readFileBytes(f.path), f.bytes);
}

TEST(Outputs, ConvertToFacesOnAFullDiskWritesNone) {
  TempDir dir;
  // Six faces, five flat and -Z noise: the -Z face, written last, is the only large file.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const char* f : {"px", "nx", "py", "ny", "pz", "nz"}) {
    Image face(128, 128, glm::vec3(0.5f));
    if (std::string(f) == "nz")
      for (auto& p : face.pixels) p = glm::vec3(u(rng), u(rng), u(rng));
    writeFileAtomic(dir / (std::string("in_") + f + ".exr"), encodeExr(face, ExrPixelType::Float));
  }
  const std::string args = "convert " + quote(dir / "in_{face}.exr") + " -o " +
                           quote(dir / "out" / "f_{face}.exr") +
                           " --layout faces --exr-type float --quiet";
  const CliRun r = runIblWithFileLimit(args, 64);
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("f_nz.exr: write failed"), std::string::npos) << r.output;
  EXPECT_TRUE(!fs::exists(dir / "out") || fs::is_empty(dir / "out")) << "faces were left";
  ASSERT_EQ(runIbl(args).status, 0);  // without the limit, all six
  EXPECT_EQ(filesIn(dir / "out").size(), 6u);
}

TEST(Outputs, BakeIntoAnExistingDirectory) {
  TempDir dir;
  const fs::path out = dir / "bake";
  ASSERT_EQ(runIbl("bake -o " + quote(out) + kQuietBake + " --size 16 --exr").status, 0);
  std::ofstream(out / "notes.txt") << "mine";
  const auto before = filesIn(out);
  ASSERT_TRUE(before.count("specular_m0.exr"));
  // Not empty: refused without --force, nothing changed.
  CliRun r = runIbl("bake -o " + quote(out) + kQuietBake + " --size 16");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(out.string() + ": exists and is not empty; pass --force"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(filesIn(out), before);
  // A failure halfway (the source cube is too large for the file limit) changes nothing.
  r = runIblWithFileLimit("bake -o " + quote(out) + kQuietBake + " --force --size 128", 256);
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("write failed"), std::string::npos) << r.output;
  EXPECT_EQ(filesIn(out), before);
  // --force without --exr: the EXR copies of the earlier bake go, the user's file stays.
  r = runIbl("bake -o " + quote(out) + kQuietBake + " --force --size 32");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto after = filesIn(out);
  EXPECT_FALSE(after.count("specular_m0.exr"));
  EXPECT_FALSE(after.count("dfg.exr"));
  EXPECT_EQ(after.at("notes.txt"), before.at("notes.txt"));
  EXPECT_EQ(readImageFile(out / "specular.ktx2").levels[0][0].width, 32);
  EXPECT_EQ(after.size(), 10u);  // the 9 outputs and notes.txt
}

TEST(Outputs, ReadersCheckABakeAgainstItsManifest) {
  TempDir dir;
  const fs::path out = dir / "bake";
  ASSERT_EQ(runIbl("bake -o " + quote(out) + kQuietBake + " --size 16").status, 0);
  const std::string render =
      "render sphere --size 8x8 --spp 1 -o " + quote(dir / "r.png") + " --bake " + quote(out);
  ASSERT_EQ(runIbl(render).status, 0);
  // A listed file replaced by another size.
  ASSERT_EQ(runIbl("convert " + quote(out / "source.ktx2") + " -o " + quote(dir / "i.ktx2") +
                   " --size 4 --quiet")
                .status,
            0);
  fs::copy_file(out / "irradiance.ktx2", dir / "kept.ktx2");
  fs::copy_file(dir / "i.ktx2", out / "irradiance.ktx2", fs::copy_options::overwrite_existing);
  CliRun r = runIbl(render);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("irradiance.ktx2: holds 1 level(s) of 6 face(s) of width 4; "
                          "manifest.json says 1 of 6 of width 32"),
            std::string::npos)
      << r.output;
  // A listed file missing.
  fs::copy_file(dir / "kept.ktx2", out / "irradiance.ktx2", fs::copy_options::overwrite_existing);
  ASSERT_EQ(runIbl(render).status, 0);
  fs::remove(out / "dfg.png");
  r = runIbl(render);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("dfg.png: is listed in manifest.json but missing"), std::string::npos)
      << r.output;
}

// A new directory is written beside its destination and renamed into place; a failure names
// the user's directory, never the staging one, and leaves neither behind.
TEST(Outputs, BakeErrorsNameTheUsersDirectory) {
  TempDir dir;
  const fs::path out = dir / "new";
  const CliRun r =
      runIblWithFileLimit("bake -o " + quote(out) + kQuietBake + " --size 128 --exr", 64);
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("ibl: error: " + out.string() + "/"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(": write failed"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("staging"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(Outputs, BakeForEngineTargets) {
  TempDir dir;
  const std::string input = quote(hdriPath("sunset"));
  // One target: its files straight into OUTDIR, named as cmgen --deploy OUTDIR names them.
  auto run =
      runIbl("bake " + input + " --size 32 --target filament --quiet -o " + quote(dir / "park"));
  ASSERT_EQ(run.status, 0) << run.output;
  for (const char* f : {"park_ibl.ktx", "park_skybox.ktx", "sh.txt", "manifest.json"})
    EXPECT_TRUE(fs::exists(dir / "park" / f)) << f;
  EXPECT_FALSE(fs::exists(dir / "park" / "specular.ktx2"));
  // Several (repeated or comma-separated): each in its own folder, ibl at the top.
  run = runIbl("bake " + input +
               " --size 32 --target ibl,dds,babylon --target gltf-sample-viewer -o " +
               quote(dir / "all") + kQuietBake + " --no-preview");
  ASSERT_EQ(run.status, 0) << run.output;
  for (const char* f : {"specular.ktx2", "sheen.ktx2", "dds/specular.dds", "dds/dfg.dds",
                        "gltf-sample-viewer/ggx/specular.ktx2", "gltf-sample-viewer/lut_ggx.png",
                        "babylon/all.env"})
    EXPECT_TRUE(fs::exists(dir / "all" / f)) << f;
  // The readers know the targets' containers.
  run = runIbl("info " + quote(dir / "all" / "dds" / "specular.dds"));
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("32x32 per face, 3 levels"), std::string::npos) << run.output;
  run = runIbl("info " + quote(dir / "all" / "babylon" / "all.env"));
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("32x32 per face, 6 levels"), std::string::npos) << run.output;
  // A contradiction: nothing written.
  run = runIbl("bake " + input + " --size 32 --target gltf-sample-viewer --mapping frostbite -o " +
               quote(dir / "bad") + kQuietBake);
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("--mapping linear"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir / "bad"));
  // A choice no requested target takes is refused, naming what the target writes instead; one
  // that some take is a note naming the others.
  const std::pair<std::string, std::string> refused[] = {
      {"--target filament --format rgba32f", "--target filament writes its fixed R11F_G11F_B10F"},
      {"--target babylon --levels 3", "--target babylon writes Babylon's chain"},
      {"--target babylon,filament --mapping frostbite", "--target filament writes cmgen's chain"},
      {"--target gltf-sample-viewer --format e5b9g9r9", "float cube maps only"},
      {"--target dds --exr", "--target dds writes DDS files"},
      {"--target filament --irradiance-size 16", "irradiance as SH9 only"}};
  for (const auto& [options, message] : refused) {
    run = runIbl("bake " + input + " --size 32 " + options + " -o " + quote(dir / "bad"));
    EXPECT_EQ(run.status, 2) << options << ": " << run.output;
    EXPECT_NE(run.output.find("ibl: error: "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find(message), std::string::npos) << options << ": " << run.output;
    EXPECT_FALSE(fs::exists(dir / "bad"));
  }
  run = runIbl("bake " + input + " --size 32 --target ibl,filament --format rgba32f -o " +
               quote(dir / "both") + " --dfg-size 16 --dfg-samples 64 --no-preview");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("ibl: note: --format applies to the ibl target(s) only: --target "
                            "filament writes its fixed R11F_G11F_B10F"),
            std::string::npos)
      << run.output;
  EXPECT_NE(readImageFile(dir / "both" / "specular.ktx2").detail.find("R32G32B32A32_SFLOAT"),
            std::string::npos);
}

namespace {

// The files under `dir` (recursively) whose names hold `piece`.
std::vector<fs::path> entriesNamed(const fs::path& dir, const std::string& piece) {
  std::vector<fs::path> found;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(piece) != std::string::npos) found.push_back(e.path());
  return found;
}

// A process id that no process has now (kill(pid, 0) fails with ESRCH).
long deadPid() {
  for (long pid = 4000000;; --pid)
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) return pid;
}

}  // namespace

// An output that is an input, by any path (the same name, "..", a symbolic link, a hard link, a
// face or level file of the output's pattern), is refused before anything is read or written:
// status 2, the input's bytes unchanged.
TEST(Outputs, OutputsThatAreInputsAreRefused) {
  TempDir dir;
  fs::copy_file(hdriPath("park"), dir / "park.exr");
  fs::create_directories(dir / "sub");
  fs::create_symlink(dir / "park.exr", dir / "link.exr");
  fs::create_hard_link(dir / "park.exr", dir / "hard.exr");
  ASSERT_EQ(runIbl("convert " + quote(dir / "park.exr") + " -o " + quote(dir / "f_{face}.exr") +
                   " --layout faces --size 8 -q")
                .status,
            0);
  const auto original = readFileBytes(dir / "park.exr");
  const auto face = readFileBytes(dir / "f_px.exr");
  const std::string park = quote(dir / "park.exr");
  const std::pair<std::string, std::string> refused[] = {
      {"convert " + park + " -o " + park, "is the input"},
      {"convert " + park + " -o " + quote(dir / "sub" / ".." / "park.exr"), "is the input"},
      {"convert " + quote(dir / "link.exr") + " -o " + park, "is the input"},
      {"convert " + park + " -o " + quote(dir / "link.exr"), "is the input"},
      {"convert " + park + " -o " + quote(dir / "new" / ".." / "link.exr"),
       "is the input"},  // through a folder the write would create
      {"convert " + quote(dir / "hard.exr") + " -o " + park + " --exr-type float", "is the input"},
      {"convert " + quote(dir / "f_{face}.exr") + " -o " + quote(dir / "f_px.exr") +
           " --layout faces",
       "is the input"},
      {"convert " + quote(dir / "f_{face}.exr") + " -o " + quote(dir / "f.exr") +
           " --layout faces --size 8",
       "is the input"},  // f_px.exr, ... are the faces of f.exr
      {"convert " + park + " -o " + quote(dir / "x.ktx2") + " --extract-sun --sun-json " + park,
       "is the input"},
      {"render sphere --size 8x8 --env " + park + " -o " + park, "is the input"},
      {"compare " + park + " " + park + " --error-png " + quote(dir / "hard.exr"), "is the input"},
      {"bake " + park + " -o " + quote(dir.path()) + " --force", "holds the input"},
      {"probe grid --at 0,0,0 --env " + park + " -o " + quote(dir.path()) + " --force",
       "holds the input"},
  };
  for (const auto& [args, message] : refused) {
    const CliRun r = runIbl(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("ibl: error: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
    EXPECT_EQ(readFileBytes(dir / "park.exr"), original) << args;
    EXPECT_EQ(readFileBytes(dir / "f_px.exr"), face) << args;
  }
  EXPECT_TRUE(entriesNamed(dir.path(), "specular").empty());
}

// What can be known wrong is found before the input is even read: the input here is not an
// image at all, so any error but the one expected would name it.
TEST(Outputs, ChecksRunBeforeTheInputIsRead) {
  TempDir dir;
  std::ofstream(dir / "broken.exr") << "not an image";
  fs::create_directories(dir / "full");
  std::ofstream(dir / "full" / "notes.txt") << "mine";
  const std::string broken = quote(dir / "broken.exr");
  const std::pair<std::string, std::string> cases[] = {
      {"bake " + broken + " -o " + quote(dir / "full"), "full: exists and is not empty"},
      {"bake " + broken + " -o " + quote(dir / "full" / "notes.txt" / "x"), "not a directory"},
      {"bake " + broken + " --target babylon --levels 3 -o " + quote(dir / "b"),
       "--levels: no target takes it"},
      {"convert " + broken + " -o " + quote(dir / "x.exr") + " --exposure 1",
       "--exposure applies to PNG"},
      {"render " + broken + " --size 8x8 --ev100 x -o " + quote(dir / "r.png"),
       "--ev100: 'x' is not a number"},
  };
  for (const auto& [args, message] : cases) {
    const CliRun r = runIbl(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
    EXPECT_EQ(r.output.find("broken.exr"), std::string::npos) << args << "\n" << r.output;
  }
  // The memory a bake needs is estimated first (IBL_MEMORY_LIMIT stands for a small machine).
  const CliRun r = runCommand("IBL_MEMORY_LIMIT=100000000 " + std::string(IBL_CLI) + " bake " +
                              broken + " --size 1024 -o " + quote(dir / "m"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("--size 1024: needs about "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("more than the 100 MB IBL_MEMORY_LIMIT allows"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "m"));
}

// A bake removes the temporaries of its own naming pattern that no live process owns (an
// earlier run killed while writing), restores a file a cut-short rename phase kept aside, and
// leaves a live process's temporaries alone.
TEST(Outputs, StaleTemporariesOfDeadProcessesAreRemoved) {
  TempDir dir;
  const fs::path out = dir / "out";
  ASSERT_EQ(runIbl("bake -o " + quote(out) + kQuietBake + " --size 16").status, 0);
  const long dead = deadPid();
  const long live = static_cast<long>(::getpid());  // this test: alive
  const auto name = [](const std::string& file, long pid, const char* tag) {
    return fmt::format("{}.{}.0.{}", file, pid, tag);
  };
  const auto sh = readFileBytes(out / "sh.json");
  std::ofstream(out / name("specular.ktx2", dead, "tmp")) << "half-written";
  std::ofstream(out / name("specular.ktx2", live, "tmp")) << "being written";
  fs::rename(out / "sh.json", out / name("sh.json", dead, "old"));  // its rename phase was cut
  std::ofstream(out / name("source.ktx2", dead, "old")) << "replaced";
  fs::create_directories(dir / fmt::format(".out.ibl-staging-{}", dead) / "sub");
  fs::create_directories(dir / fmt::format(".out.ibl-staging-{}", live));
  const CliRun r = runIbl("bake -o " + quote(out) + kQuietBake + " --size 16 --force");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(fs::exists(out / name("specular.ktx2", dead, "tmp")));
  EXPECT_FALSE(fs::exists(out / name("source.ktx2", dead, "old")));  // its file is there
  EXPECT_FALSE(fs::exists(out / name("sh.json", dead, "old")));
  EXPECT_EQ(readFileBytes(out / "sh.json"), sh);  // restored, then rewritten alike
  EXPECT_FALSE(fs::exists(dir / fmt::format(".out.ibl-staging-{}", dead)));
  EXPECT_TRUE(fs::exists(out / name("specular.ktx2", live, "tmp")));
  EXPECT_TRUE(fs::exists(dir / fmt::format(".out.ibl-staging-{}", live)));
}

// Ctrl-C while a bake writes: the process exits with 128 + SIGINT and leaves none of its
// temporaries, and the output directory is either absent or whole. The interrupt is sent as
// soon as the first temporary appears (the encoding before takes most of the time).
TEST(Outputs, InterruptsRemoveTheProcesssTemporaries) {
  TempDir dir;
  for (const bool existing : {false, true}) {
    const fs::path out = dir / (existing ? "existing" : "new");
    if (existing) {
      ASSERT_EQ(runIbl("bake -o " + quote(out) + kQuietBake + " --size 16").status, 0);
    }
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      const std::string o = out.string();
      ::execl(IBL_CLI, IBL_CLI, "bake", "-o", o.c_str(), "--size", "256", "--exr", "--hdr",
              "--force", "--quiet", static_cast<char*>(nullptr));
      std::_Exit(127);
    }
    bool interrupted = false;
    int status = 0;
    while (::waitpid(child, &status, WNOHANG) == 0) {
      if (!interrupted && (!entriesNamed(dir.path(), ".tmp").empty() ||
                           !entriesNamed(dir.path(), "ibl-staging").empty())) {
        ::kill(child, SIGINT);
        interrupted = true;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    if (!interrupted) GTEST_SKIP() << "the bake ended before its write phase was seen";
    ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
    // The interrupt may come as the last file moves into place: then the bake is whole.
    const bool finished = WEXITSTATUS(status) == 0;
    if (!finished) {
      EXPECT_EQ(WEXITSTATUS(status), 128 + SIGINT);
    }
    EXPECT_TRUE(entriesNamed(dir.path(), ".tmp").empty());
    EXPECT_TRUE(entriesNamed(dir.path(), ".old").empty());
    EXPECT_TRUE(entriesNamed(dir.path(), "ibl-staging").empty());
    if (!existing && finished) {
      EXPECT_EQ(readImageFile(out / "specular.ktx2").levels[0][0].width, 256);
    } else if (!existing && fs::exists(out)) {  // moved into place as the interrupt came
      EXPECT_TRUE(fs::exists(out / "manifest.json"));
      EXPECT_TRUE(fs::exists(out / "specular_m0.exr"));
    } else if (existing) {  // the earlier bake, or the new one: whole either way
      const auto size = readImageFile(out / "specular.ktx2").levels[0][0].width;
      EXPECT_TRUE(size == 16 || size == 256) << size;
      if (size == 256) {
        EXPECT_TRUE(fs::exists(out / "specular_m0.exr"));
      }
    }
  }
}

// Every command that writes checks its outputs before any work: a path under a regular file
// (which no one may create, root included) fails at once with one line naming it, and nothing
// is written. The inputs here are not what they claim (broken.exr is no image, broken.gltf no
// glTF): an error naming them would show that the work started first. Missing folders of an
// output are created, by every command alike.
TEST(Outputs, UnwritableOutputsFailBeforeTheWork) {
  TempDir dir;
  std::ofstream(dir / "file") << "a regular file";
  std::ofstream(dir / "broken.exr") << "not an image";
  std::ofstream(dir / "broken.gltf") << "not a glTF file";
  const std::string exr = quote(dir / "broken.exr"), gltf = quote(dir / "broken.gltf");
  const auto under = [&](const std::string& name) { return (dir / "file" / name).string(); };
  const std::pair<std::string, std::string> cases[] = {
      {"render " + gltf + " --size 8x8 -o ", under("r.png")},
      {"render sphere --env " + exr + " --size 8x8 -o ", under("r.exr")},
      {"sky --size 16x8 --device gpu -o ", under("s.exr")},
      {"sky --size 16x8 --sun-json " + quote(dir / "new" / "sun.json") + " -o ", under("s.hdr")},
      {"view " + gltf + " --size 8x8 --screenshot ", under("v.png")},
      {"convert " + exr + " -o ", under("c.hdr")},
      {"convert " + exr + " --layout faces -o ", under("f_{face}.exr")},
      {"compare " + exr + " " + exr + " --error-png ", under("e.png")},
      {"probe " + gltf + " --at 0,0,0 -o ", under("p")},
      {"bake " + exr + " -o ", under("b")},
  };
  for (const auto& [args, output] : cases) {
    const CliRun r = runIbl(args + quote(output));
    EXPECT_EQ(r.status, 1) << args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("ibl: error: ", 0), 0u) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find("file is not a directory"), std::string::npos) << args << r.output;
    EXPECT_EQ(r.output.find("broken"), std::string::npos) << args << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "new"));
  // A folder the user may not write (permissions do not stop root: then the check is moot).
  if (::geteuid() != 0) {
    fs::create_directories(dir / "locked");
    fs::permissions(dir / "locked", fs::perms::owner_read | fs::perms::owner_exec);
    const CliRun r = runIbl("render " + gltf + " -o " + quote(dir / "locked" / "sub" / "r.png"));
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("r.png: cannot be written in " + (dir / "locked").string()),
              std::string::npos)
        << r.output;
    fs::permissions(dir / "locked", fs::perms::owner_all);
    EXPECT_TRUE(fs::is_empty(dir / "locked"));
  }
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::recursive_directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, fs::exists(dir / "locked") ? 4 : 3);
  // Missing folders are created: an image, a sky and its lights file, a bake.
  ASSERT_EQ(runIbl("render sphere --env none --size 8x8 --spp 1 -q -o " +
                   quote(dir / "a" / "b" / "r.png"))
                .status,
            0);
  EXPECT_TRUE(fs::is_regular_file(dir / "a" / "b" / "r.png"));
  ASSERT_EQ(runIbl("sky --size 16x8 -q -o " + quote(dir / "c" / "s.exr") + " --sun-json " +
                   quote(dir / "d" / "e" / "sun.json"))
                .status,
            0);
  EXPECT_TRUE(fs::is_regular_file(dir / "c" / "s.exr"));
  EXPECT_TRUE(fs::is_regular_file(dir / "d" / "e" / "sun.json"));
  ASSERT_EQ(runIbl("bake sky:elevation=30 --size 16" + kQuietBake + " -o " +
                   quote(dir / "f" / "g" / "bake"))
                .status,
            0);
  EXPECT_TRUE(fs::is_regular_file(dir / "f" / "g" / "bake" / "manifest.json"));
}
