#pragma once
// Internal: the text encodings of binary data and names that file formats embed (the glTF
// loader's buffers and images): base64 (RFC 4648), data URIs (RFC 2397) and percent-encoding
// (RFC 3986).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ibl {

// A data URI: "data:[<mime type>][;base64],<payload>".
struct DataUri {
  std::string mimeType;
  bool base64 = false;
  std::string_view payload;
};

// Splits a data URI into its parts.
// @param uri  the URI; the payload returned is a view into it.
// @return nullopt if `uri` does not start with "data:"; an empty DataUri if it has no comma.
std::optional<DataUri> parseDataUri(std::string_view uri);

// The number of bytes base64 text decodes to (padding optional), without decoding it.
// @param text  base64 text, with or without its trailing '=' padding; not checked.
std::uint64_t base64Size(std::string_view text);

// Decodes base64 (RFC 4648, standard or URL alphabet, padding optional).
// @param text  the base64 text.
// @return the bytes; nullopt if `text` is not base64 (a character outside both alphabets, or a
//         length that leaves a single character in the last group).
std::optional<std::vector<std::uint8_t>> decodeBase64(std::string_view text);

// Decodes a relative URI's %XX escapes (RFC 3986 section 2.1).
// @param s  the URI; a '%' not followed by two hexadecimal digits is kept as it is.
std::string percentDecode(std::string_view s);

}  // namespace ibl
