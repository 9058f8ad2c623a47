#pragma once
// API: internal (may change without notice; exposes nlohmann::json)
// Reading a JSON file (manifests, probe grids, shard lists) with the one error message for
// every reader.
#include <filesystem>

#include <nlohmann/json_fwd.hpp>

namespace ibl {

// Reads and parses a whole JSON file. Throws Error("<path>: no such file") and the other
// readFileBytes errors, or Error("<path>: not valid JSON: <parser's message>").
nlohmann::json readJsonFile(const std::filesystem::path& path);

}  // namespace ibl
