// include/ibl/shared/charlie_table.h (written by tools/charlie_table.cpp) against the projected
// area it tabulates, computed here at every node, and its bilinear lookup
// (shared::charlieLambdaTabulated) against the exact Smith Lambda between the nodes.
// ibl::charlieProjectedArea itself is checked against its closed forms and 2D quadrature in
// tests/bake/test_sheen.cpp (Sheen.ProjectedAreaMatchesQuadratureAndItsClosedForms).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "ibl/math/brdf.hpp"
#include "ibl/shared/brdf.h"
#include "ibl/shared/charlie_table.h"
#include "support/numbers.hpp"

using namespace ibl;
using namespace ibl::test;

TEST(CharlieTable, HoldsTheProjectedArea) {
  // Every entry of ibl/shared/charlie_table.h is r A(theta, r^2) at its node (the file is what
  // tools/charlie_table.cpp writes from charlieProjectedArea); between the nodes the bilinear
  // lookup (charlieLambdaTabulated) stays within 1.3 % of 1 + Lambda (measured 1.2 %, near the
  // normal, where Lambda is small).
  const int rows = shared::kCharlieTableRoughnesses, columns = shared::kCharlieTableAngles;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      const double r = std::max(static_cast<double>(j) / (rows - 1), 1e-3);
      const double theta = 0.5 * kPi * i / (columns - 1);
      const double expected = r * charlieProjectedArea(theta, r * r, 20000);
      EXPECT_NEAR(shared::kCharlieProjectedArea[j * columns + i], expected, 2e-7 + 1e-6 * expected)
          << "row " << j << " column " << i;
    }
  double worst = 0.0;
  for (double r : {0.004, 0.013, 0.07, 0.1, 0.21, 0.31, 0.55, 0.77, 0.97})
    for (double mu : {0.003, 0.05, 0.2, 0.37, 0.6, 0.8, 0.93, 0.99}) {
      const double exact = charlieProjectedArea(std::acos(mu), r * r) / mu;
      const double table =
          1.0 + shared::charlieLambdaTabulated(static_cast<float>(mu), static_cast<float>(r * r));
      worst = std::max(worst, std::abs(table / exact - 1.0));
      EXPECT_NEAR(table / exact, 1.0, 0.013) << "r " << r << " mu " << mu;
    }
  std::printf("tabulated Charlie Lambda: 1 + Lambda within %.2f %% of the exact\n", 100.0 * worst);
}
