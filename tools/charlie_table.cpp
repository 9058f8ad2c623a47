// ibl_charlie_table: tabulates the exact Smith Lambda of the Charlie sheen distribution and writes
// it as the shared header the library and the shaders compile in:
//   ibl_charlie_table [OUTPUT.h]   (default include/ibl/shared/charlie_table.h)
// The table holds r A(theta, r^2): the microsurface's projected area (ibl::charlieProjectedArea)
// times the sheen roughness r, which stays finite as r goes to 0 (the area grows as 1 / r: the
// fibres stand up), at r = j / (R - 1) (row j; r = 0.001 for row 0) and theta = (pi / 2) i / (C -
// 1) (column i). shared::charlieLambdaTabulated (ibl/shared/brdf.h) interpolates it bilinearly:
// within 1.3 % of 1 + Lambda from r = 0.004 to 1 at every angle (the worst near the normal, where
// Lambda is small).
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "ibl/math/brdf.hpp"

namespace {

constexpr int kRoughnesses = 33, kAngles = 17;
constexpr double kSmallestRoughness = 0.001;

}  // namespace

int main(int argc, char** argv) {
  const std::string output = argc > 1 ? argv[1] : "include/ibl/shared/charlie_table.h";
  std::string text = fmt::format(
      "// API: internal (may change without notice; math shared with the shaders)\n"
      "// Written by tools/charlie_table.cpp (ibl_charlie_table); do not edit. r A(theta, r^2), "
      "the Charlie\n"
      "// microsurface's projected area (ibl::charlieProjectedArea) times the sheen roughness r, "
      "at\n"
      "// r = j / {} (row j; r = {} for row 0) and theta = (pi / 2) i / {} (column i), for\n"
      "// shared::charlieLambdaTabulated (ibl/shared/brdf.h). The sizes are C++ and GLSL (see "
      "lang.h);\n"
      "// the values are C++ only: the shaders read them from a buffer (charlieTableEntry).\n"
      "#ifndef IBL_SHARED_CHARLIE_TABLE_H\n"
      "#define IBL_SHARED_CHARLIE_TABLE_H\n"
      "#include \"ibl/shared/lang.h\"\n\n"
      "IBL_BEGIN\n\n"
      "const int kCharlieTableRoughnesses = {};\n"
      "const int kCharlieTableAngles = {};\n"
      "const float kCharlieTableSmallestRoughness = {}f;\n"
      "\n"
      "#ifdef __cplusplus\n"
      "// clang-format off\n"
      "inline constexpr float kCharlieProjectedArea[{}] = {{\n",
      kRoughnesses - 1, kSmallestRoughness, kAngles - 1, kRoughnesses, kAngles, kSmallestRoughness,
      kRoughnesses * kAngles);
  for (int j = 0; j < kRoughnesses; ++j) {
    const double r = std::max(static_cast<double>(j) / (kRoughnesses - 1), kSmallestRoughness);
    text += "   ";
    for (int i = 0; i < kAngles; ++i) {
      const double theta = 0.5 * std::numbers::pi * i / (kAngles - 1);
      const double value = r * ibl::charlieProjectedArea(theta, r * r, 20000);
      const bool last = j == kRoughnesses - 1 && i == kAngles - 1;
      text += fmt::format(" {:.7f}f{}", value, last ? "" : ",");
      if (i % 6 == 5 && i + 1 < kAngles) text += "\n   ";
    }
    text += "\n";
  }
  text += "};\n// clang-format on\n#endif\n\nIBL_END\n\n#endif\n";
  std::ofstream file(output);
  if (!(file << text)) {
    std::cerr << "ibl_charlie_table: " << output << ": cannot write\n";
    return 1;
  }
  std::cout << "wrote " << output << " (" << kRoughnesses << " x " << kAngles << ")\n";
  return 0;
}
