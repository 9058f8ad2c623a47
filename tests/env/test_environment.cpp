#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/equirect.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/ktx2.hpp"
#include "support/exr_writer.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

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

TEST(Environment, StripsOfFaces) {
  const int n = 4;
  for (const Layout layout : {Layout::HStrip, Layout::VStrip}) {
    const bool horizontal = layout == Layout::HStrip;
    Image strip(horizontal ? 6 * n : n, horizontal ? n : 6 * n);
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
          strip.at(horizontal ? f * n + x : x, horizontal ? y : f * n + y) =
              glm::vec3(static_cast<float>(f), static_cast<float>(x), static_cast<float>(y));
    DecodedFile file;
    file.levels = {{strip}};
    const Environment env = environmentFromFile(std::move(file), {}, "strip.exr");
    ASSERT_EQ(env.layout, layout);
    for (int f = 0; f < 6; ++f)
      EXPECT_EQ(env.cube.levels[0][f].at(3, 1), glm::vec3(static_cast<float>(f), 3.0f, 1.0f));
    EXPECT_EQ(flatFromCube(env.cube, 0, layout).pixels, strip.pixels);
  }
}

// A mirror ball and an angular map of a known environment (the direction as a color), drawn
// here from the reflection law and the angle-to-radius rule, are read back as that environment.
TEST(Environment, MirrorBallAndAngularMaps) {
  const auto color = [](glm::vec3 d) { return 0.5f * (d + 1.0f); };
  const int w = 256;
  for (const Layout layout : {Layout::MirrorBall, Layout::Angular}) {
    Image probe(w, w);
    for (int y = 0; y < w; ++y)
      for (int x = 0; x < w; ++x) {
        const double px = 2.0 * (x + 0.5) / w - 1.0, py = 1.0 - 2.0 * (y + 0.5) / w;
        const double r2 = px * px + py * py;
        if (r2 > 1.0) continue;
        glm::dvec3 d;
        if (layout == Layout::MirrorBall) {  // reflect (0, 0, -1) about the ball's normal
          const glm::dvec3 normal(px, py, std::sqrt(1.0 - r2));
          const glm::dvec3 view(0.0, 0.0, -1.0);
          d = view - 2.0 * glm::dot(view, normal) * normal;
        } else {  // the angle from +Z is pi times the radius
          const double r = std::sqrt(r2), a = 3.141592653589793 * r;
          d = r > 0 ? glm::dvec3(std::sin(a) * px / r, std::sin(a) * py / r, std::cos(a))
                    : glm::dvec3(0, 0, 1);
        }
        probe.at(x, y) = color(glm::vec3(d));
      }
    DecodedFile file;
    file.levels = {{probe}};
    const Environment env = environmentFromFile(std::move(file), {layout, ""}, "probe.exr");
    ASSERT_FALSE(env.isCube());
    for (const glm::vec3 d :
         {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, -1, 0),
          glm::vec3(0, 0, 1), glm::vec3(0.6f, 0.0f, -0.8f), glm::normalize(glm::vec3(1, 2, 3))}) {
      const glm::vec3 got = sampleEquirect(env.equirect, d);
      EXPECT_LT(glm::length(got - color(d)), 0.03f)
          << layoutName(layout) << " " << d.x << "," << d.y << "," << d.z;
    }
  }
}
