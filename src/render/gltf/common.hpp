#pragma once
// Internal to the glTF loader (src/render/gltf/): the small helpers its parts share: messages
// naming an index, overflow-safe arithmetic on the file's counts, and byte ranges decoded once.
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <map>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace ibl::gltf {

using u64 = std::uint64_t;
constexpr u64 kU64Max = std::numeric_limits<u64>::max();

// "material 99 out of range (the file has 3)"
// @param what   what the index names ("material").
// @param index  the index as the file gives it.
// @param count  how many of `what` the file has.
inline std::string outOfRange(std::string_view what, long long index, std::size_t count) {
  if (count == 0) return fmt::format("{} {} out of range (the file has none)", what, index);
  return fmt::format("{} {} out of range (the file has {})", what, index, count);
}

// Whether `index` names one of `count` things.
inline bool inRange(long long index, std::size_t count) {
  return index >= 0 && static_cast<u64>(index) < count;
}

// a * b and a + b, or 2^64 - 1 where they overflow.
inline u64 saturatingMul(u64 a, u64 b) {
  return b != 0 && a > kU64Max / b ? kU64Max : a * b;
}
inline u64 saturatingAdd(u64 a, u64 b) {
  return a > kU64Max - b ? kU64Max : a + b;
}

// The first line of `s`, cut to 200 characters: a library's message in a one-line error.
inline std::string firstLine(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  if (line.size() > 200) line = line.substr(0, 200) + "...";
  return line;
}

// "1.5 MiB": `bytes` in the largest binary unit it reaches.
inline std::string formatBytes(u64 bytes) {
  if (bytes >= (u64{1} << 30))
    return fmt::format("{:.1f} GiB", static_cast<double>(bytes) / 0x1p30);
  if (bytes >= (u64{1} << 20))
    return fmt::format("{:.1f} MiB", static_cast<double>(bytes) / 0x1p20);
  if (bytes >= (u64{1} << 10))
    return fmt::format("{:.1f} KiB", static_cast<double>(bytes) / 0x1p10);
  return fmt::format("{} bytes", bytes);
}

// Byte ranges of buffers, each to be decoded once: a range may be added again as it is (the
// caller reuses what it made of it), not overlap another in part.
class DisjointRanges {
 public:
  // Whether [start, end) of `buffer` equals or misses every range added so far; adds it.
  bool add(int buffer, u64 start, u64 end) {
    if (start == end) return true;
    std::map<u64, u64>& ranges = ranges_[buffer];
    const auto next = ranges.lower_bound(start);
    if (next != ranges.end() && next->first == start && next->second == end) return true;
    if (next != ranges.end() && next->first < end) return false;
    if (next != ranges.begin() && std::prev(next)->second > start) return false;
    ranges.emplace(start, end);
    return true;
  }

 private:
  std::map<int, std::map<u64, u64>> ranges_;
};

}  // namespace ibl::gltf
