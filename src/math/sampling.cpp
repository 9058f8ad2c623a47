#include "ibl/math/sampling.hpp"

#include <array>
#include <cstddef>

namespace ibl {

namespace {

constexpr std::uint32_t reverseBits(std::uint32_t x) {
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
// v_k = v_(k-1) ^ (v_(k-1) >> 1) (the Pascal matrix), as bits from the top. The point is the XOR
// of the direction numbers of the index's set bits: one entry per byte of the index from four
// 256-entry tables. The tables hold the numbers bit-reversed, as the Owen scramble reads them.
struct SobolDimension1Tables {
  std::array<std::array<std::uint32_t, 256>, 4> reversed{};
  constexpr SobolDimension1Tables() {
    std::array<std::uint32_t, 32> v{};
    v[0] = 1u << 31u;
    for (std::size_t k = 1; k < v.size(); ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1u);
    for (std::size_t b = 0; b < 4; ++b)
      for (std::uint32_t x = 0; x < 256; ++x)
        for (std::uint32_t bit = 0; bit < 8; ++bit)
          if (x & (1u << bit)) reversed[b][x] ^= reverseBits(v[8 * b + bit]);
  }
};
// Built by the compiler: no static-initialization order to depend on.
constexpr SobolDimension1Tables kSobolDimension1;

// reverseBits(point `index` of Sobol's dimension 1).
std::uint32_t sobolDimension1Reversed(std::uint32_t index) {
  const auto& t = kSobolDimension1.reversed;
  return t[0][index & 0xffu] ^ t[1][(index >> 8u) & 0xffu] ^ t[2][(index >> 16u) & 0xffu] ^
         t[3][index >> 24u];
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
  // together, so prefixes of 2^k points stay (0,k,2)-nets. owenScramble(x, s) is
  // reverseBits(laineKarrasPermutation(reverseBits(x), s)); written out here so that no bits are
  // reversed twice: the shuffled index's reversal is dimension 0 (van der Corput) unscrambled.
  const std::uint32_t x = laineKarrasPermutation(reverseBits(index), hash32(seed));
  const std::uint32_t i = reverseBits(x);
  return {toUnit(reverseBits(laineKarrasPermutation(i, hash32(seed ^ 0x9e3779b9u)))),
          toUnit(reverseBits(
              laineKarrasPermutation(sobolDimension1Reversed(i), hash32(seed ^ 0x85ebca6bu))))};
}

}  // namespace ibl
