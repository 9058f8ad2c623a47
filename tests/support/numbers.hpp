#pragma once
// Pi for the tests' own computations, in double and in float precision.
#include <numbers>

namespace ibl::test {

inline constexpr double kPi = std::numbers::pi;
inline constexpr float kPiF = std::numbers::pi_v<float>;

}  // namespace ibl::test
