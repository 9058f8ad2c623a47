#pragma once
// The key/value data of KTX 1.1 and KTX 2.0, which both versions lay out the same way: per
// pair a uint32 keyAndValueByteSize, the key and the value each followed by NUL, then padding
// to a multiple of 4 bytes.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ibl/core/error.hpp"
#include "little_endian.hpp"

namespace ibl {

using KtxKeyValues = std::vector<std::pair<std::string, std::string>>;

inline std::vector<std::uint8_t> encodeKtxKeyValues(const KtxKeyValues& pairs) {
  std::vector<std::uint8_t> kvd;
  for (const auto& [key, value] : pairs) {
    const auto length = static_cast<std::uint32_t>(key.size() + 1 + value.size() + 1);
    const std::size_t at = kvd.size();
    kvd.resize(at + 4);
    le::put32(kvd, at, length);
    kvd.insert(kvd.end(), key.begin(), key.end());
    kvd.push_back(0);
    kvd.insert(kvd.end(), value.begin(), value.end());
    kvd.push_back(0);
    kvd.resize(le::alignUp(kvd.size(), 4), 0);
  }
  return kvd;
}

// The pairs stored in bytes [begin, begin + length) of `b` (already checked to lie inside it).
inline KtxKeyValues decodeKtxKeyValues(std::span<const std::uint8_t> b, std::uint64_t begin,
                                       std::uint64_t length, std::string_view name) {
  KtxKeyValues pairs;
  const std::uint64_t end = begin + length;
  for (std::uint64_t at = begin; at + 4 <= end;) {
    const std::uint32_t len = le::get32(b, at);
    if (len == 0 || len > end - at - 4) fail(name, "corrupt key/value entry");
    const std::string entry(reinterpret_cast<const char*>(b.data() + at + 4), len);
    const auto nul = entry.find('\0');
    if (nul == std::string::npos) fail(name, "key/value entry without a terminated key");
    std::string value = entry.substr(nul + 1);
    if (!value.empty() && value.back() == '\0') value.pop_back();
    pairs.emplace_back(entry.substr(0, nul), value);
    at = le::alignUp(at + 4 + len, 4);
  }
  return pairs;
}

}  // namespace ibl
