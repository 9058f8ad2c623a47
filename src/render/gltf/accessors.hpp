#pragma once
// Internal to the glTF loader: reading accessors (glTF 2.0 3.6.2): their elements' components,
// normalized or not, through a stride, with sparse substitution.
#include <cstddef>
#include <cstdint>

namespace ibl::gltf {

// An accessor, checked: where its elements are and how to read them.
struct AccessorLayout {
  const std::uint8_t* data = nullptr;  // the first element; null: every element is zero
  std::size_t stride = 0, count = 0, elementSize = 0;
  int componentType = 0, components = 0;
  bool normalized = false, matrix = false;
  // Sparse (glTF 2.0 3.6.2.3): `sparseCount` increasing element indices, and their values
  // (tightly packed elements).
  std::size_t sparseCount = 0;
  const std::uint8_t* sparseIndices = nullptr;
  int sparseIndexType = 0;
  const std::uint8_t* sparseValues = nullptr;
};

// The bytes of one component of a glTF component type (5120 BYTE to 5126 FLOAT).
// @param componentType  the accessor's componentType.
// @return 1, 2 or 4; 0 for a value that is not a glTF component type.
std::size_t componentSize(int componentType);

// The glTF accessor type of `components` components: "SCALAR", "VEC2", "VEC3", "VEC4", or
// "a matrix" for any other count.
const char* typeName(int components);

// Component `i` of an array of unsigned integers.
// @param p              the array's first byte (no alignment needed).
// @param componentType  UNSIGNED_BYTE or UNSIGNED_SHORT; any other type is read as UNSIGNED_INT.
// @param i              the component's index.
std::uint32_t unsignedAt(const std::uint8_t* p, int componentType, std::size_t i);

// Element `i` of a checked accessor as floats (normalized integers mapped to [0, 1] or [-1, 1]).
// @param a    the accessor, checked (i < a.count).
// @param i    the element's index.
// @param out  receives a.components floats; zeros for an element without data.
void readFloats(const AccessorLayout& a, std::size_t i, float* out);

// Element `i` of a checked accessor of unsigned integer scalars (an index accessor); 0 for an
// element without data.
std::uint32_t readIndex(const AccessorLayout& a, std::size_t i);

}  // namespace ibl::gltf
