// Writes small valid files of every format into fuzz/seeds/<reader>/ to start the fuzzers.
#include <filesystem>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfTiledOutputFile.h>

#include "ibl/io/babylon_env.hpp"
#include "ibl/io/dds.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/ktx1.hpp"
#include "ibl/io/ktx2.hpp"

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  const fs::path root = argc > 1 ? argv[1] : "fuzz/seeds";
  ibl::Image img(9, 4);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    img.pixels[i] = glm::vec3(float(i % 5), float(i % 3) * 0.25f, 100.0f / float(i + 1));
  ibl::writeFileAtomic(root / "hdr" / "small.hdr", ibl::encodeHdr(img));
  ibl::writeFileAtomic(root / "hdr" / "narrow.hdr",
                       ibl::encodeHdr(ibl::Image(3, 2, glm::vec3(1.0f))));
  ibl::writeFileAtomic(root / "exr" / "half.exr", ibl::encodeExr(img, ibl::ExrPixelType::Half));
  ibl::writeFileAtomic(root / "exr" / "float.exr", ibl::encodeExr(img, ibl::ExrPixelType::Float));
  ibl::writeFileAtomic(root / "ldr" / "small.png", ibl::encodePng(img));
  for (auto f : {ibl::PixelFormat::Rgba16f, ibl::PixelFormat::E5B9G9R9}) {
    ibl::Ktx2Texture tex;
    tex.format = f;
    tex.faceCount = 6;
    tex.levels.resize(2);
    for (int m = 0; m < 2; ++m)
      for (int face = 0; face < 6; ++face)
        tex.levels[m].push_back(ibl::Image(2 >> m, 2 >> m, glm::vec3(0.5f)));
    ibl::writeFileAtomic(root / "ktx2" / (std::string(ibl::formatName(f)) + ".ktx2"),
                         ibl::encodeKtx2(tex));
  }
  // KTX1 as Filament's cmgen writes it, and DDS cube maps and 2D textures.
  {
    std::vector<std::vector<ibl::Image>> cube(2);
    for (int m = 0; m < 2; ++m)
      for (int face = 0; face < 6; ++face)
        cube[m].push_back(ibl::Image(2 >> m, 2 >> m, glm::vec3(0.5f)));
    ibl::writeFileAtomic(
        root / "ktx1" / "cmgen.ktx",
        ibl::encodeKtx1({ibl::PixelFormat::B10G11R11, 6, cube, {{"sh", "1 2 3\n"}}}));
    ibl::writeFileAtomic(root / "ktx1" / "rgba16f.ktx",
                         ibl::encodeKtx1({ibl::PixelFormat::Rgba16f, 1, {{img}}, {}}));
    ibl::writeFileAtomic(root / "dds" / "cube.dds",
                         ibl::encodeDds({ibl::PixelFormat::Rgba16f, 6, cube}));
    ibl::BabylonEnvironment env;
    env.width = 2;
    env.levels = cube;
    env.levels[1][3] = ibl::Image(1, 1, glm::vec3(300.0f));  // beyond RGBD's range
    ibl::writeFileAtomic(root / "env" / "babylon.env", ibl::encodeBabylonEnv(env));
    ibl::writeFileAtomic(root / "dds" / "rg11b10.dds",
                         ibl::encodeDds({ibl::PixelFormat::B10G11R11, 1, {{img}}}));
  }
  // Small files in the codecs and layouts real HDRIs use, written by OpenEXR itself.
  std::vector<Imath::half> px(16 * 16 * 3, Imath::half(0.75f));
  for (auto [compression, name] :
       {std::pair{Imf::DWAB_COMPRESSION, "dwab"}, std::pair{Imf::PIZ_COMPRESSION, "piz"},
        std::pair{Imf::B44_COMPRESSION, "b44"}}) {
    for (bool tiled : {false, true}) {
      Imf::Header header(16, 16);
      header.compression() = compression;
      Imf::FrameBuffer fb;
      for (int c = 0; c < 3; ++c) {
        header.channels().insert(std::string(1, "RGB"[c]), Imf::Channel(Imf::HALF));
        fb.insert(std::string(1, "RGB"[c]),
                  Imf::Slice(Imf::HALF, reinterpret_cast<char*>(px.data() + c), 6, 6 * 16));
      }
      const fs::path path = root / "exr" / (std::string(name) + (tiled ? "_tiled" : "") + ".exr");
      if (tiled) {
        header.setTileDescription(Imf::TileDescription(8, 8, Imf::ONE_LEVEL));
        Imf::TiledOutputFile file(path.c_str(), header);
        file.setFrameBuffer(fb);
        file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
      } else {
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(16);
      }
    }
  }
  return 0;
}
