// API: internal (may change without notice; math shared with the shaders)
// The prelude of every header in ibl/shared/: the math written once for the CPU and the GPU.
//
// A header in this folder compiles both as C++20 (included by the library, through the C++
// headers of math/, env/, bake/ and render/) and as GLSL 4.50 (included by the shaders under
// shaders/, which glslc compiles with -I include). glm mirrors GLSL's types and built-in
// functions, so one text serves both; what differs is settled here:
//   - IBL_FN before every function: `inline` (and always inlined, for the vectorized loops) in
//     C++, nothing in GLSL;
//   - IBL_INOUT(T) for a parameter the function updates (T& in C++, inout T in GLSL), and
//     IBL_FLOAT_BITS(x) for a float's bits as a uint (std::bit_cast, floatBitsToUint);
//   - IBL_BEGIN / IBL_END around the definitions: namespace ibl::shared in C++ (the C++
//     headers export what the library uses into namespace ibl), nothing in GLSL;
//   - structs are built member by member (no constructors, no braces), arrays are avoided,
//     literals carry the `f` suffix (a float in both), conversions are written as float(x),
//     and no name is a GLSL keyword (sample, input, output, filter, ...).
#ifndef IBL_SHARED_LANG_H
#define IBL_SHARED_LANG_H

#ifdef __cplusplus
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#define IBL_FN [[gnu::always_inline]] inline
#define IBL_BEGIN namespace ibl::shared {
#define IBL_END }
#define IBL_INOUT(T) T&
#define IBL_FLOAT_BITS(x) std::bit_cast<std::uint32_t>(x)
// A struct member's default value: C++ only (GLSL's structs have none; shaders set each member).
#define IBL_DEFAULT(x) = x

namespace ibl::shared {
using uint = std::uint32_t;
using glm::ivec2;
using glm::ivec3;
using glm::mat3;
using glm::vec2;
using glm::vec3;
using glm::vec4;

// GLSL's built-in functions, as glm defines them (glm also brings std's scalar overloads).
using glm::abs;
using glm::acos;
using glm::asin;
using glm::atan;
using glm::ceil;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::exp2;
using glm::floor;
using glm::fract;
using glm::length;
using glm::log;
using glm::log2;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::pow;
using glm::sin;
using glm::sqrt;
}  // namespace ibl::shared
#else
#define IBL_FN
#define IBL_BEGIN
#define IBL_END
#define IBL_INOUT(T) inout T
#define IBL_FLOAT_BITS(x) floatBitsToUint(x)
#define IBL_DEFAULT(x)
#endif

IBL_BEGIN
// pi rounded to a float (std::numbers::pi_v<float>).
const float kPi = 3.14159265358979f;
IBL_END

#endif
