#pragma once
// The Vulkan compute context the GPU tests share: one per test executable, made on first use.
#include <memory>

#include "ibl/gpu/compute.hpp"

namespace ibl::test {

inline gpu::Context& context() {
  static const std::unique_ptr<gpu::Context> c = gpu::Context::create();
  return *c;
}

}  // namespace ibl::test
