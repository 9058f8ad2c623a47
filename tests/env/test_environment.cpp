#include <fstream>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/ktx2.hpp"
#include "support/exr_writer.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Environment, LayoutFromShape) {
  EXPECT_EQ(layoutFromShape(1024, 512), Layout::Equirect);
  EXPECT_EQ(layoutFromShape(400, 300), Layout::HCross);
  EXPECT_EQ(layoutFromShape(300, 400), Layout::VCross);
  EXPECT_EQ(layoutFromShape(500, 400), std::nullopt);
}

TEST(Environment, LoadsEquirectAndCountsInvalidPixels) {
  const LoadedEnvironment studio = loadEnvironment(hdriPath("studio").string());
  EXPECT_EQ(studio.format, "exr");
  EXPECT_EQ(studio.environment.layout, Layout::Equirect);
  EXPECT_EQ(studio.replaced.negative, 2028u);
  EXPECT_EQ(countInvalidPixels(studio.environment.equirect).total(), 0u);
}

TEST(Environment, ReplacesNanAndInfinity) {
  TempDir dir;
  Image img(8, 4, glm::vec3(1.0f));
  img.at(1, 1) = glm::vec3(NAN, INFINITY, -2.0f);
  img.at(2, 2).x = -INFINITY;
  writeExrWithOpenExr(img, dir / "bad.exr");  // ibl's own encoder writes no NaN or infinity
  const LoadedEnvironment env = loadEnvironment((dir / "bad.exr").string());
  EXPECT_EQ(env.replaced.nan, 1u);
  EXPECT_EQ(env.replaced.infinite, 2u);
  EXPECT_EQ(env.replaced.negative, 1u);
  EXPECT_EQ(env.environment.equirect.at(1, 1), glm::vec3(0.0f));
}

TEST(Environment, LoadsCrossFacesAndKtx2Cubes) {
  TempDir dir;
  const CubeMap cube = cubeFromFunction(8, [](glm::vec3 d) { return glm::abs(d) + 0.1f; });
  writeFileAtomic(dir / "cross.exr", encodeExr(crossFromCube(cube, 0, true), ExrPixelType::Float));
  const LoadedEnvironment v = loadEnvironment((dir / "cross.exr").string());
  EXPECT_EQ(v.environment.layout, Layout::VCross);
  EXPECT_EQ(v.environment.cube.levels[0][5].pixels, cube.levels[0][5].pixels);

  for (int f = 0; f < 6; ++f)
    writeFileAtomic(facePath(dir / "sky_{face}.hdr", f), encodeHdr(cube.levels[0][f]));
  const LoadedEnvironment faces = loadEnvironment((dir / "sky_{face}.hdr").string());
  EXPECT_EQ(faces.environment.layout, Layout::Faces);
  EXPECT_NEAR(faces.environment.cube.levels[0][3].at(4, 4).y, cube.levels[0][3].at(4, 4).y, 0.01f);

  Ktx2Texture tex;
  tex.format = PixelFormat::Rgba32f;
  tex.faceCount = 6;
  tex.levels = {{cube.levels[0].begin(), cube.levels[0].end()}};
  writeFileAtomic(dir / "cube.ktx2", encodeKtx2(tex));
  const LoadedEnvironment k = loadEnvironment((dir / "cube.ktx2").string());
  EXPECT_EQ(k.environment.layout, Layout::Cube);
  EXPECT_EQ(k.environment.cube.levels[0][2].pixels, cube.levels[0][2].pixels);
}

TEST(Environment, ClearErrorsNameTheFile) {
  TempDir dir;
  const std::string missing = (dir / "nope.hdr").string();
  EXPECT_EQ(errorOf([&] { loadEnvironment(missing); }), missing + ": no such file");
  std::ofstream(dir / "empty.exr").close();
  EXPECT_EQ(errorOf([&] { loadEnvironment((dir / "empty.exr").string()); }),
            (dir / "empty.exr").string() + ": empty file");
  std::ofstream(dir / "text.hdr") << "hello world";
  EXPECT_NE(
      errorOf([&] { loadEnvironment((dir / "text.hdr").string()); }).find("unknown file format"),
      std::string::npos);
  writeFileAtomic(dir / "square.exr", encodeExr(Image(16, 16)));
  EXPECT_NE(errorOf([&] {
              loadEnvironment((dir / "square.exr").string());
            }).find("cannot tell the layout"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { loadEnvironment(dir.path().string()); }).find("is a directory"),
            std::string::npos);
}

TEST(FileIo, AtomicWriteLeavesNoTemporaryFiles) {
  TempDir dir;
  const std::vector<std::uint8_t> bytes = {1, 2, 3};
  writeFileAtomic(dir / "sub" / "a.bin", bytes);
  EXPECT_EQ(readFileBytes(dir / "sub" / "a.bin"), bytes);
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir / "sub")) ++files;
  EXPECT_EQ(files, 1);
  // A path whose directory cannot be created fails cleanly.
  writeFileAtomic(dir / "file", bytes);
  EXPECT_THROW(writeFileAtomic(dir / "file" / "x.bin", bytes), Error);
}
