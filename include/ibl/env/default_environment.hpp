#pragma once
// API: internal (may change without notice; the bundled default of the command-line front end)
// The bundled default environment: data/hdri/sunset.exr (512 x 256 half-float DWAB EXR with a
// visible sun; CC0, Poly Haven), compiled into the library.
#include <cstdint>
#include <span>

namespace ibl {

inline constexpr const char* kDefaultEnvironmentName = "sunset.exr";
// The EXR file's bytes (static storage), for loadEnvironmentFromMemory.
std::span<const std::uint8_t> defaultEnvironmentBytes();

}  // namespace ibl
