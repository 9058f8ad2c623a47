#pragma once
// API: internal (may change without notice; exposes nlohmann::json)
// Reading JSON (manifests, probe grids, shard lists, lights files) with the one error message
// for every reader: the file, the line and column, and the problem.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace ibl {

// Parses a JSON text (strictly: one value, nothing after it) into nlohmann::json or
// nlohmann::ordered_json. Throws Error("<name>: line L, column C: <problem>"), the problem in
// words ("unexpected end of input; expected '}'", "the number 1e999 is out of range"), any
// byte that is not printable ASCII shown as \xNN.
template <typename Json>
Json parseJsonText(std::string_view text, const std::string& name);

// "line L, column C" of the character at `offset` bytes into `text` (lines end with '\n'; the
// column counts bytes from 1; an offset at or past the end is the place after the last byte).
std::string jsonTextPosition(std::string_view text, std::size_t offset);

// "line L, column C: <problem>" for the error nlohmann's parser reports to a SAX handler's
// parse_error(charactersRead, lastToken, exception): the place of the offending character (of
// the number's start, for a number out of range, exception id 406) and the message in words.
std::string describeJsonError(std::string_view text, std::size_t charactersRead,
                              const std::string& lastToken, int exceptionId,
                              const std::string& message);

// Reads and parses a whole JSON file. Throws Error("<path>: no such file") and the other
// readFileBytes errors, or parseJsonText's Error naming the path.
nlohmann::json readJsonFile(const std::filesystem::path& path);

}  // namespace ibl
