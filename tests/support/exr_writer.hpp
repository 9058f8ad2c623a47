#pragma once
// EXR files written by the OpenEXR library itself (an independent writer: any compression,
// tiled or not, and values ibl's own encoder never writes, such as NaN and infinities).
#include <cstdint>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfTiledOutputFile.h>

#include "ibl/core/image.hpp"
#include "ibl/io/file_io.hpp"
#include "support/helpers.hpp"

namespace ibl::test {

// Writes an RGB float image with the OpenEXR library itself, in the given compression, as a
// scanline or tiled file, with a data window that does not start at the origin.
inline std::vector<std::uint8_t> writeWithOpenExr(const Image& img, Imf::Compression compression,
                                                  bool tiled, Imf::PixelType type,
                                                  const TempDir& dir) {
  const auto path = (dir / "ref.exr").string();
  const Imath::Box2i dataWindow({10, 20}, {10 + img.width - 1, 20 + img.height - 1});
  Imf::Header header(dataWindow, dataWindow);
  header.compression() = compression;
  for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(type));
  std::vector<float> planes[3];
  std::vector<Imath::half> halves[3];
  Imf::FrameBuffer fb;
  for (int c = 0; c < 3; ++c) {
    planes[c].resize(img.pixels.size());
    halves[c].resize(img.pixels.size());
    for (std::size_t i = 0; i < img.pixels.size(); ++i) {
      planes[c][i] = img.pixels[i][c];
      halves[c][i] = Imath::half(img.pixels[i][c]);
    }
    void* base = type == Imf::HALF ? static_cast<void*>(halves[c].data()) : planes[c].data();
    const std::size_t size = type == Imf::HALF ? 2 : 4;
    fb.insert(std::string(1, "RGB"[c]),
              Imf::Slice::Make(type, base, dataWindow, size, size * img.width));
  }
  if (tiled) {
    header.setTileDescription(Imf::TileDescription(16, 16, Imf::ONE_LEVEL));
    Imf::TiledOutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
  } else {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(img.height);
  }
  return readFileBytes(path);
}

// The same as a file: `path`, float, ZIP, scanlines.
inline void writeExrWithOpenExr(const Image& img, const std::filesystem::path& path) {
  TempDir scratch;
  writeFileAtomic(path, writeWithOpenExr(img, Imf::ZIP_COMPRESSION, false, Imf::FLOAT, scratch));
}

}  // namespace ibl::test
