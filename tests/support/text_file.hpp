#pragma once
// A whole file as text, for the tests that read the repository's own files.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace ibl::test {

// The bytes of `path` as a string; empty when it cannot be read.
inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace ibl::test
