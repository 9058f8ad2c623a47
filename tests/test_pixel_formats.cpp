#include <gtest/gtest.h>
#include "ibl/pixel_formats.hpp"
TEST(PixelFormats, HalfRoundTrip) { EXPECT_EQ(ibl::halfToFloat(ibl::floatToHalf(1.5f)), 1.5f); }
