#pragma once
// The compute shaders (shaders/{env,bake}/*.comp), compiled to SPIR-V by glslc at build time.
#include <cstdint>
#include <span>
#include <string_view>

namespace ibl::gpu {

// SPIR-V words of shader `name` (the file name without .comp); empty if unknown.
std::span<const std::uint32_t> spirvFor(std::string_view name);

}  // namespace ibl::gpu
