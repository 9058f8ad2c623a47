// Errors and limits (ibl/core/error.hpp): the one-line "<what>: <problem>" message, usage errors
// as their own kind, and the image size limits at their edges (65536 per side, 2^28 pixels).
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

TEST(Errors, MessagesNameWhatIsAtFault) {
  EXPECT_EQ(errorOf([] { fail("sky.hdr", "truncated"); }), "sky.hdr: truncated");
  try {
    failUsage("--size", "must be a power of two");
    ADD_FAILURE() << "no error";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()), "--size: must be a power of two");
  }
}

TEST(Errors, ImageSizesAreCheckedAtTheLimits) {
  EXPECT_NO_THROW(checkImageSize("a.exr", 1, 1));
  EXPECT_NO_THROW(checkImageSize("a.exr", 65536, 4096));  // 2^28 pixels exactly
  EXPECT_EQ(errorOf([] { checkImageSize("a.exr", 0, 5); }), "a.exr: empty image (0x5)");
  EXPECT_EQ(errorOf([] { checkImageSize("a.exr", 7, 0); }), "a.exr: empty image (7x0)");
  EXPECT_EQ(errorOf([] { checkImageSize("a.exr", 65537, 1); }),
            "a.exr: image of 65537x1 exceeds the limit (65536 per side, 268435456 pixels)");
  EXPECT_NE(errorOf([] { checkImageSize("a.exr", 1, 65537); }).find("exceeds the limit"),
            std::string::npos);
  EXPECT_NE(errorOf([] { checkImageSize("a.exr", 65536, 4097); }).find("exceeds the limit"),
            std::string::npos);
}
