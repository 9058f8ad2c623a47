// Reading any image file (ibl/io/image_io.hpp): formats told by their signatures, the bytes'
// first and never the name; and every file under tests/corpus/ (hostile inputs written by hand,
// and crashes the fuzzers found) must be rejected with ibl::Error or decoded, never crash or hang.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

TEST(Regressions, HostileInputsAreRejectedCleanly) {
  const std::filesystem::path corpus = std::filesystem::path(IBL_TEST_DIR) / "corpus";
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(corpus)) {
    if (!entry.is_regular_file()) continue;
    ++files;
    const auto bytes = readFileBytes(entry.path());
    try {
      const DecodedFile d = decodeImageFile(bytes, entry.path().string());
      EXPECT_FALSE(d.levels.empty());
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
  EXPECT_GT(files, 5);
}

// Each format's signature, as its specification gives it (Radiance's "#?", OpenEXR's magic
// number 20000630, PNG's eight bytes, JPEG's SOI marker and a segment, KTX 2's and KTX 1's
// identifiers, "DDS ", Babylon's eight bytes), with bytes of another kind after it.
TEST(ImageIo, FormatsAreToldByTheirFirstBytes) {
  const std::vector<std::pair<std::vector<std::uint8_t>, FileFormat>> signatures = {
      {{'#', '?', 'R', 'A'}, FileFormat::Hdr},
      {{0x76, 0x2f, 0x31, 0x01, 0x02}, FileFormat::Exr},
      {{0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a, 0}, FileFormat::Png},
      {{0xff, 0xd8, 0xff, 0xe0}, FileFormat::Jpg},
      {{0xab, 'K', 'T', 'X', ' ', '2', '0', 0xbb, 0x0d, 0x0a, 0x1a, 0x0a}, FileFormat::Ktx2},
      {{0xab, 'K', 'T', 'X', ' ', '1', '1', 0xbb, 0x0d, 0x0a, 0x1a, 0x0a}, FileFormat::Ktx1},
      {{'D', 'D', 'S', ' ', 124}, FileFormat::Dds},
      {{0x86, 0x16, 0x87, 0x96, 0xf6, 0xd6, 0x96, 0x36, '{'}, FileFormat::BabylonEnv}};
  for (const auto& [bytes, format] : signatures)
    EXPECT_EQ(detectFileFormat(bytes), format) << fileFormatName(format);
  // A signature one byte short, or with one byte changed, is none.
  const std::vector<std::uint8_t> ktx2 = signatures[4].first;
  EXPECT_FALSE(detectFileFormat(std::vector<std::uint8_t>(ktx2.begin(), ktx2.end() - 1)));
  std::vector<std::uint8_t> png = signatures[2].first;
  png[4] = 0x0a;
  EXPECT_FALSE(detectFileFormat(png));
  EXPECT_FALSE(detectFileFormat(std::vector<std::uint8_t>{'G', 'I', 'F', '8'}));
  EXPECT_EQ(fileFormatFromExtension("a/b.JPEG"), FileFormat::Jpg);
  EXPECT_EQ(fileFormatFromExtension("sky.pic"), FileFormat::Hdr);
  EXPECT_FALSE(fileFormatFromExtension("sky.dds"));  // written, never chosen by its name
  EXPECT_EQ(errorOf([] { decodeImageFile({}, "e.hdr"); }), "e.hdr: empty file");
  const std::vector<std::uint8_t> gif = {'G', 'I', 'F', '8', '9', 'a'};
  EXPECT_EQ(errorOf([&] { decodeImageFile(gif, "x.hdr"); }).rfind("x.hdr: unknown file format", 0),
            0u);
}
