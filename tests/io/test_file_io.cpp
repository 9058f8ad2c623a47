// Files written atomically (ibl/io/file_io.hpp): the bytes land whole under their name, no
// temporary is left beside them, and a path that cannot be made fails cleanly.
#include <cstdint>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

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

// 6:1 and 1:6 strips hold faces +X -X +Y -Y +Z -Z in order, in their native orientation; the
// shape alone tells them, and writing one back gives the same image.
