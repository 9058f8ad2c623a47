#pragma once
// Little-endian fields of the binary containers (KTX 1, KTX 2, DDS): every one of them stores
// its header words little-endian, whatever the machine.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace ibl::le {

inline void put32(std::vector<std::uint8_t>& out, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}
inline void put64(std::vector<std::uint8_t>& out, std::size_t at, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}
inline std::uint32_t get32(std::span<const std::uint8_t> b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(b[at + i]) << (8 * i);
  return v;
}
inline std::uint64_t get64(std::span<const std::uint8_t> b, std::size_t at) {
  return get32(b, at) | (static_cast<std::uint64_t>(get32(b, at + 4)) << 32);
}
inline std::size_t alignUp(std::size_t v, std::size_t a) {
  return (v + a - 1) / a * a;
}

}  // namespace ibl::le
