// The reference's numbers (ibl/shared/path_sampler.h): Sobol's dimension 1 against its
// generator matrix built here (Pascal's triangle mod 2: column k holds row k of it), the byte
// tables the CPU reads against the shaders' loop, and a pixel's stream of numbers drawn in pairs,
// one at a time or in a branch that leaves the stream where it was.
#include <cstdint>

#include <gtest/gtest.h>

#include "ibl/math/sampling.hpp"
#include "ibl/shared/path_sampler.h"

using namespace ibl;

namespace {

// Point i of Sobol's dimension 1 as a 32-bit fraction, from the Pascal matrix: its digit j
// (weight 2^-(j+1)) is the parity of the sum over k of C(k, j) i_k, i_k the index's bits; C(k, j)
// is odd exactly when j's bits are a subset of k's (Lucas's theorem).
std::uint32_t sobolDimension1(std::uint32_t index) {
  std::uint32_t point = 0;
  for (std::uint32_t j = 0; j < 32; ++j) {
    std::uint32_t digit = 0;
    for (std::uint32_t k = 0; k < 32; ++k)
      if ((index >> k & 1u) && (k & j) == j) digit ^= 1u;
    point |= digit << (31 - j);
  }
  return point;
}

std::uint32_t reversed(std::uint32_t x) {
  std::uint32_t r = 0;
  for (int b = 0; b < 32; ++b) r |= (x >> b & 1u) << (31 - b);
  return r;
}

}  // namespace

TEST(PathSampler, SobolDimension1IsThePascalMatrixsSequence) {
  for (std::uint32_t i : {0u, 1u, 2u, 3u, 5u, 255u, 256u, 0x12345u, 0xdeadbeefu, 0xffffffffu}) {
    EXPECT_EQ(shared::sobolDimension1Reversed(i), reversed(sobolDimension1(i))) << i;
    EXPECT_EQ(sobolDimension1ReversedFromTables(i), shared::sobolDimension1Reversed(i)) << i;
  }
  // The first points: 0, 1/2, 3/4, 1/4.
  EXPECT_EQ(sobolDimension1(1), 0x80000000u);
  EXPECT_EQ(sobolDimension1(2), 0xc0000000u);
  EXPECT_EQ(sobolDimension1(3), 0x40000000u);
}

TEST(PathSampler, NumbersComeInPairsAndBranchesLeaveTheStream) {
  const std::uint32_t key = shared::pathSamplerKey(7u, 0u, 12u, 0u);
  EXPECT_NE(key, shared::pathSamplerKey(7u, 0u, 13u, 0u));  // another pixel
  shared::PathSampler pairs = shared::pathSamplerAt(key, 3u);
  shared::PathSampler singles = pairs;
  for (int d = 0; d < 4; ++d) {
    const glm::vec2 pair = shared::pathUniform2(pairs);
    EXPECT_GE(pair.x, 0.0f);
    EXPECT_LT(pair.y, 1.0f);
    EXPECT_EQ(shared::pathUniform(singles), pair.x) << d;
    const shared::PathSampler branch = shared::pathSamplerBranch(singles);
    EXPECT_EQ(branch.index, 3u);
    EXPECT_EQ(shared::pathUniform(singles), pair.y) << d;
  }
  // The same sample of the same pixel draws the same numbers; the next sample others.
  shared::PathSampler again = shared::pathSamplerAt(key, 3u), next = shared::pathSamplerAt(key, 4u);
  const glm::vec2 first = shared::pathUniform2(again);
  shared::PathSampler same = shared::pathSamplerAt(key, 3u);
  EXPECT_EQ(first, shared::pathUniform2(same));
  EXPECT_NE(first, shared::pathUniform2(next));
}
