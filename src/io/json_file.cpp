#include "ibl/io/json_file.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"

namespace ibl {

nlohmann::json readJsonFile(const std::filesystem::path& path) {
  const auto bytes = readFileBytes(path);
  try {
    return nlohmann::json::parse(bytes.begin(), bytes.end());
  } catch (const nlohmann::json::exception& e) {
    fail(path.string(), fmt::format("not valid JSON: {}", e.what()));
  }
}

}  // namespace ibl
