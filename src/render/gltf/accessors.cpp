#include "accessors.hpp"

#include <algorithm>
#include <cstring>

#include <tiny_gltf.h>

namespace ibl::gltf {

namespace {

float componentAt(const std::uint8_t* p, int type, int c, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p + 4 * c, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? p[c] / 255.0f : p[c];
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const auto v = static_cast<signed char>(p[c]);
      return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p + 2 * c, 2);
      return normalized ? v / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p + 2 * c, 2);
      return normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    default: {  // UNSIGNED_INT: not an attribute type (checked before reading)
      std::uint32_t v;
      std::memcpy(&v, p + 4 * c, 4);
      return static_cast<float>(v);
    }
  }
}

// The address of element i, its sparse value where there is one (binary search among the
// increasing indices); null for an element that is zero.
const std::uint8_t* elementAt(const AccessorLayout& a, std::size_t i) {
  if (a.sparseCount) {
    std::size_t lo = 0, hi = a.sparseCount;
    while (lo < hi) {
      const std::size_t mid = lo + (hi - lo) / 2;
      const std::uint32_t at = unsignedAt(a.sparseIndices, a.sparseIndexType, mid);
      if (at == i) return a.sparseValues + mid * a.elementSize;
      if (at < i)
        lo = mid + 1;
      else
        hi = mid;
    }
  }
  return a.data ? a.data + i * a.stride : nullptr;
}

}  // namespace

std::size_t componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

const char* typeName(int components) {
  switch (components) {
    case 1:
      return "SCALAR";
    case 2:
      return "VEC2";
    case 3:
      return "VEC3";
    case 4:
      return "VEC4";
    default:
      return "a matrix";
  }
}

std::uint32_t unsignedAt(const std::uint8_t* p, int componentType, std::size_t i) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return p[i];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p + 2 * i, 2);
      return v;
    }
    default: {
      std::uint32_t v;
      std::memcpy(&v, p + 4 * i, 4);
      return v;
    }
  }
}

void readFloats(const AccessorLayout& a, std::size_t i, float* out) {
  const std::uint8_t* p = elementAt(a, i);
  for (int c = 0; c < a.components; ++c)
    out[c] = p ? componentAt(p, a.componentType, c, a.normalized) : 0.0f;
}

std::uint32_t readIndex(const AccessorLayout& a, std::size_t i) {
  const std::uint8_t* p = elementAt(a, i);
  return p ? unsignedAt(p, a.componentType, 0) : 0;
}

}  // namespace ibl::gltf
