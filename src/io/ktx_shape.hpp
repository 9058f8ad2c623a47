#pragma once
// The shape checks KTX 1.1 and KTX 2.0 share (src/io/ktx1.cpp, src/io/ktx2.cpp): what a file's
// header may declare for the readers (a 2D texture or a cube map with its mip levels), and what a
// texture must hold for the writers (1 or 6 faces on every level, each of the level's size).
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "ibl/core/image.hpp"

namespace ibl {

// The shape a KTX header declares, in either version's fields.
struct KtxShape {
  std::uint32_t width = 0, height = 0;  // pixelWidth, pixelHeight
  std::uint32_t depth = 0;              // pixelDepth
  std::uint32_t layers = 0;             // KTX1 numberOfArrayElements, KTX2 layerCount
  std::uint32_t faces = 0;              // KTX1 numberOfFaces, KTX2 faceCount
  std::uint32_t levels = 0;             // KTX1 numberOfMipmapLevels, KTX2 levelCount
};

// How a version names the face and level counts in its messages ("numberOfFaces", "faceCount").
struct KtxFieldNames {
  std::string_view faces;
  std::string_view levels;
};

// Checks the header's shape as the readers take it.
//   name:   the file, for messages;
//   shape:  the header's fields;
//   fields: the version's names of the face and level counts.
// Throws Error("<name>: <problem>") for a 1D or 3D texture, an array, a face count other than 1
// or 6, cube faces that are not square, a size out of checkImageSize's limits or more levels
// than a full mip chain. Returns the number of levels to read: the declared count, or 1 where it
// is 0 ("generate mipmaps": the one stored level).
std::uint32_t checkKtxShape(std::string_view name, const KtxShape& shape,
                            const KtxFieldNames& fields);

// Checks that a texture to write has levels and a valid face count.
//   codec:      "ktx1" or "ktx2", for messages;
//   levelCount: the texture's number of mip levels;
//   faceCount:  its number of faces.
// Throws Error("<codec>: ...") unless there is a level and 1 or 6 faces.
void checkKtxLevelCount(std::string_view codec, std::size_t levelCount, int faceCount);

// Checks one level of a texture to write.
//   codec:         "ktx1" or "ktx2", for messages;
//   faces:         the level's faces;
//   level:         its index (0: the largest);
//   faceCount:     the texture's number of faces;
//   width, height: the size of level 0.
// Throws Error("<codec>: level <level> ...") unless the level has faceCount faces, each of the
// level's size, max(1, width >> level) x max(1, height >> level).
void checkKtxLevel(std::string_view codec, const std::vector<Image>& faces, std::size_t level,
                   int faceCount, int width, int height);

}  // namespace ibl
