// ibl_ltc_fit: fits the GGX table of linearly transformed cosines (ibl/render/ltc.hpp) and
// writes it as the C++ source the library compiles in:
//   ibl_ltc_fit [OUTPUT.inc] [--size N] [--samples S] [--exponent K] [--errors]
//   (default src/render/ltc_table.inc, N = 64, S = 32, K = 1; Heitz et al. 2016's K is 3)
// The file holds M^-1 (kLtcTable) and the lobe's norm, Fresnel term and mean direction
// (kLtcNormTable); its header records the fit error reached (the L1 distance between the
// normalized GGX lobe and its LTC, per entry).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "ibl/render/ltc.hpp"

int main(int argc, char** argv) {
  std::string output = "src/render/ltc_table.inc";
  int size = 64;
  ibl::LtcFitOptions options;
  bool printErrors = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--size" && i + 1 < argc) {
      size = std::atoi(argv[++i]);
    } else if (arg == "--samples" && i + 1 < argc) {
      options.samples = std::atoi(argv[++i]);
    } else if (arg == "--exponent" && i + 1 < argc) {
      options.exponent = std::atoi(argv[++i]);
    } else if (arg == "--errors") {
      printErrors = true;
    } else if (arg == "-h" || arg == "--help") {
      std::cout << "usage: ibl_ltc_fit [OUTPUT.inc] [--size N] [--samples S] [--exponent K] "
                   "[--errors]\n"
                   "  --samples   the objective's samples, S^2 of each distribution (32)\n"
                   "  --exponent  the objective, the integral of |GGX - LTC|^K (1 or 3; 1)\n"
                   "  --errors    print every entry's fit error (rows: n.v, columns: roughness)\n";
      return 0;
    } else {
      output = arg;
    }
  }
  if (size < 2 || size > 256) {
    std::cerr << "ibl_ltc_fit: --size must be in [2, 256]\n";
    return 1;
  }
  if (options.samples < 4 || (options.exponent != 1 && options.exponent != 3)) {
    std::cerr << "ibl_ltc_fit: --samples must be at least 4, --exponent 1 or 3\n";
    return 1;
  }
  const auto start = std::chrono::steady_clock::now();
  const std::vector<ibl::LtcFit> fits = ibl::fitLtcTable(
      size,
      [](float f) { std::cerr << fmt::format("\rfitting: {:3.0f} %", 100.0f * f) << std::flush; },
      options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double mean = 0.0;
  std::size_t worst = 0;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    mean += fits[i].error / static_cast<double>(fits.size());
    if (fits[i].error > fits[worst].error) worst = i;
  }
  if (printErrors) {
    std::cerr << "\n";
    for (int row = 0; row < size; ++row) {
      std::cerr << fmt::format("n.v {:.3f}:", ibl::ltcRowCosTheta(row, size));
      for (int column = 0; column < size; ++column)
        std::cerr << fmt::format(" {:.3f}",
                                 fits[static_cast<std::size_t>(row) * size + column].error);
      std::cerr << "\n";
    }
  }
  const int worstRow = static_cast<int>(worst) / size, worstColumn = static_cast<int>(worst) % size;
  std::string text = fmt::format(
      "// The GGX table of linearly transformed cosines (ibl/render/ltc.hpp), {0} x {0} entries "
      "of\n"
      "// M^-1 (ibl/shared/ltc.h), row-major: row i at sqrt(1 - n.v) = i / {1}, column j at\n"
      "// perceptual roughness j / {1}; then the lobe's (norm, Fresnel term, mean direction x, z)\n"
      "// at the same places. Written by ibl_ltc_fit (tools/ltc_fit.cpp; {7}^2 samples of each\n"
      "// distribution, |GGX - LTC|^{8}) in {2:.0f} s; do not edit. Fit error (L1 distance\n"
      "// between the normalized lobe and its LTC, 0..2):\n"
      "// mean {3:.4f}, max {4:.4f} (roughness {5:.3f}, n.v {6:.3f}).\n"
      "constexpr int kLtcTableSize = {0};\n"
      "constexpr float kLtcTable[] = {{\n",
      size, size - 1, seconds, mean, fits[worst].error,
      static_cast<float>(worstColumn) / static_cast<float>(size - 1),
      ibl::ltcRowCosTheta(worstRow, size), options.samples, options.exponent);
  // A float literal: 8 significant digits, with a point or an exponent ("1.0f", not "1f").
  const auto literal = [](float x) {
    std::string t = fmt::format("{:.8g}", x);
    if (t.find_first_of(".en") == std::string::npos) t += ".0";
    return t + "f";
  };
  const auto row = [&](glm::vec4 v) {
    return fmt::format("    {}, {}, {}, {},\n", literal(v.x), literal(v.y), literal(v.z),
                       literal(v.w));
  };
  for (const ibl::LtcFit& f : fits) text += row(f.entry);
  text += "};\nconstexpr float kLtcNormTable[] = {\n";
  for (const ibl::LtcFit& f : fits)
    text +=
        row(glm::vec4(f.norm.norm, f.norm.fresnel, f.norm.meanDirection.x, f.norm.meanDirection.y));
  text += "};\n";
  const std::string temporary = output + ".tmp";
  {
    std::ofstream out(temporary);
    out << text;
    if (!out) {
      std::cerr << "\nibl_ltc_fit: " << output << ": cannot write\n";
      return 1;
    }
  }
  std::rename(temporary.c_str(), output.c_str());
  std::cerr << fmt::format("\rfitted {0} x {0} in {1:.1f} s; error mean {2:.4f}, max {3:.4f}\n",
                           size, seconds, mean, fits[worst].error);
  return 0;
}
