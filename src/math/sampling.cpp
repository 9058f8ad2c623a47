#include "ibl/math/sampling.hpp"

namespace ibl {

namespace {

std::uint32_t reverseBits(std::uint32_t x) {
  x = (x << 16u) | (x >> 16u);
  x = ((x & 0x00FF00FFu) << 8u) | ((x & 0xFF00FF00u) >> 8u);
  x = ((x & 0x0F0F0F0Fu) << 4u) | ((x & 0xF0F0F0F0u) >> 4u);
  x = ((x & 0x33333333u) << 2u) | ((x & 0xCCCCCCCCu) >> 2u);
  x = ((x & 0x55555555u) << 1u) | ((x & 0xAAAAAAAAu) >> 1u);
  return x;
}

// Burley 2020, listing 1: a permutation of the high bits that depends only on lower bits.
std::uint32_t laineKarrasPermutation(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Dimension 1 of Sobol (primitive polynomial x + 1): direction numbers v_1 = 2^31,
// v_k = v_(k-1) ^ (v_(k-1) >> 1) (the Pascal matrix), as bits from the top.
std::uint32_t sobolDimension1(std::uint32_t index) {
  std::uint32_t result = 0, v = 1u << 31u;
  for (; index != 0; index >>= 1u, v ^= v >> 1u)
    if (index & 1u) result ^= v;
  return result;
}

float toUnit(std::uint32_t bits) {
  return static_cast<float>(bits >> 8u) * (1.0f / 16777216.0f);  // 24 bits: exact, < 1
}

}  // namespace

std::uint32_t hash32(std::uint32_t x) {
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return x;
}

std::uint32_t owenScramble(std::uint32_t x, std::uint32_t seed) {
  return reverseBits(laineKarrasPermutation(reverseBits(x), seed));
}

glm::vec2 sobolOwen2D(std::uint32_t index, std::uint32_t seed) {
  // Shuffling the index by an Owen scramble keeps every aligned block of 2^k indices
  // together, so prefixes of 2^k points stay (0,k,2)-nets.
  const std::uint32_t i = owenScramble(index, hash32(seed));
  const std::uint32_t x = reverseBits(i);  // dimension 0: van der Corput
  const std::uint32_t y = sobolDimension1(i);
  return {toUnit(owenScramble(x, hash32(seed ^ 0x9e3779b9u))),
          toUnit(owenScramble(y, hash32(seed ^ 0x85ebca6bu)))};
}

}  // namespace ibl
