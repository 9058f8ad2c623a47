#include "ibl/math/sampling.hpp"

#include <array>
#include <cstddef>

namespace ibl {

namespace {

// Dimension 1 of Sobol (primitive polynomial x + 1): direction numbers v_1 = 2^31,
// v_k = v_(k-1) ^ (v_(k-1) >> 1) (the Pascal matrix), as bits from the top. The point is the XOR
// of the direction numbers of the index's set bits: one entry per byte of the index from four
// 256-entry tables. The tables hold the numbers bit-reversed, as the Owen scramble reads them.
struct SobolDimension1Tables {
  std::array<std::array<std::uint32_t, 256>, 4> reversed{};
  constexpr SobolDimension1Tables() {
    // Reversed, v_1 = 2^31 is r_1 = 1 and v_k = v_(k-1) ^ (v_(k-1) >> 1) is
    // r_k = r_(k-1) ^ (r_(k-1) << 1).
    std::array<std::uint32_t, 32> r{};
    r[0] = 1u;
    for (std::size_t k = 1; k < r.size(); ++k) r[k] = r[k - 1] ^ (r[k - 1] << 1u);
    for (std::size_t b = 0; b < 4; ++b)
      for (std::uint32_t x = 0; x < 256; ++x)
        for (std::uint32_t bit = 0; bit < 8; ++bit)
          if (x & (1u << bit)) reversed[b][x] ^= r[8 * b + bit];
  }
};
// Built by the compiler: no static-initialization order to depend on.
constexpr SobolDimension1Tables kSobolDimension1;

}  // namespace

std::uint32_t sobolDimension1ReversedFromTables(std::uint32_t index) {
  const auto& t = kSobolDimension1.reversed;
  return t[0][index & 0xffu] ^ t[1][(index >> 8u) & 0xffu] ^ t[2][(index >> 16u) & 0xffu] ^
         t[3][index >> 24u];
}

}  // namespace ibl
