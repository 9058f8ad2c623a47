// Every file under tests/corpus/ (hostile inputs written by hand, and crashes the fuzzers
// found) must be rejected with ibl::Error or decoded, never crash or hang.
#include <filesystem>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"

using namespace ibl;

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
