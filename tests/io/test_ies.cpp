// IES (LM-63) profiles: files written here from known distributions, read back and interpolated,
// integrated against the distribution's closed-form flux, and malformed files rejected with the
// line named.
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/io/ies.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// An LM-63-2002 file of `f(vertical, horizontal)` (degrees) sampled on the given angles, each
// value stored divided by `scale` (the file's candela multiplier 2 times its ballast factor
// scale / 2 gives it back), the candela values of each plane on a line of their own.
std::string iesFile(const std::function<double(double, double)>& f,
                    const std::vector<double>& vertical, const std::vector<double>& horizontal,
                    double scale = 1.0) {
  std::string s = "IESNA:LM-63-2002\n[TEST] written by the ibl tests\n[MANUFAC] none\nTILT=NONE\n";
  s += fmt::format("1 -1 2 {} {} 1 2 0 0 0\n{} 1 100\n", vertical.size(), horizontal.size(),
                   scale / 2.0);
  for (double v : vertical) s += fmt::format("{} ", v);
  s += "\n";
  for (double h : horizontal) s += fmt::format("{}, ", h);  // commas delimit too
  s += "\n";
  for (double h : horizontal) {
    for (double v : vertical) s += fmt::format("{:.9g} ", f(v, h) / scale);
    s += "\n";
  }
  return s;
}

std::vector<double> steps(double from, double to, double step) {
  std::vector<double> out;
  for (double a = from; a <= to + 1e-9; a += step) out.push_back(a);
  return out;
}

}  // namespace

// A distribution with no symmetry, I = 500 + 400 cos(theta) + 100 sin^2(theta) cos(2 phi) + 50
// sin(theta) sin(phi), on a 5 x 15 degree web: exact at the nodes, within 0.6 % of the peak
// between them, and its flux the closed form 500 * 4 pi (the other terms integrate to zero).
TEST(Ies, ReadsAWebAndInterpolatesIt) {
  const auto f = [](double v, double h) {
    return 500.0 + 400.0 * std::cos(v * kDeg) +
           100.0 * std::pow(std::sin(v * kDeg), 2) * std::cos(2.0 * h * kDeg) +
           50.0 * std::sin(v * kDeg) * std::sin(h * kDeg);
  };
  const IesProfile p = parseIes(iesFile(f, steps(0, 180, 5), steps(0, 360, 15), 4.0), "web.ies");
  EXPECT_EQ(p.vertical.size(), 37u);
  EXPECT_EQ(p.horizontal.size(), 25u);
  EXPECT_FLOAT_EQ(p.lampLumens, -1.0f);
  double nodeMax = 0.0;
  for (double v : steps(0, 180, 5))
    for (double h : steps(0, 360, 15)) nodeMax = std::max(nodeMax, f(v, h));
  EXPECT_NEAR(p.maxCandela(), nodeMax, 0.01);
  for (double v : {0.0, 35.0, 90.0, 180.0})
    for (double h : {0.0, 45.0, 210.0, 345.0})
      EXPECT_NEAR(p.intensity(static_cast<float>(v), static_cast<float>(h)), f(v, h), 0.01)
          << v << " " << h;
  double worst = 0.0;
  for (double v = 1.3; v < 180.0; v += 3.7)
    for (double h = -20.0; h < 380.0; h += 7.3)
      worst = std::max(worst, std::abs(p.intensity(static_cast<float>(v), static_cast<float>(h)) -
                                       f(v, std::fmod(h + 360.0, 360.0))));
  EXPECT_LT(worst, 0.006 * 1000.0);
  EXPECT_NEAR(p.flux() / (500.0 * 4.0 * std::numbers::pi), 1.0, 2e-3);
}

// Each symmetry the format allows, written with only the planes it needs, gives the full
// distribution back at any horizontal angle.
TEST(Ies, UnfoldsEachSymmetry) {
  struct Case {
    const char* name;
    std::function<double(double, double)> f;
    std::vector<double> horizontal;
  };
  const auto s2 = [](double v) { return std::pow(std::sin(v * kDeg), 2); };
  const std::vector<Case> cases = {
      {"quadrants",
       [&](double v, double h) { return 300.0 + 100.0 * s2(v) * std::cos(2.0 * h * kDeg); },
       steps(0, 90, 10)},
      {"bilateral 0-180",
       [&](double v, double h) { return 300.0 + 100.0 * s2(v) * std::cos(h * kDeg); },
       steps(0, 180, 10)},
      {"bilateral 90-270",
       [&](double v, double h) { return 300.0 + 100.0 * s2(v) * std::sin(h * kDeg); },
       steps(90, 270, 10)},
      {"axial", [&](double v, double) { return 300.0 + 100.0 * s2(v); }, {0.0}}};
  for (const Case& c : cases) {
    const IesProfile p = parseIes(iesFile(c.f, steps(0, 180, 5), c.horizontal), c.name);
    for (double h = 0.0; h < 360.0; h += 12.5)
      for (double v : {30.0, 90.0, 140.0})
        EXPECT_NEAR(p.intensity(static_cast<float>(v), static_cast<float>(h)), c.f(v, h), 1.5)
            << c.name << " at " << v << ", " << h;
  }
}

// A downlight measured over the lower hemisphere only emits nothing upward; a single bright
// value among zeros interpolates without ringing below zero or above the peak.
TEST(Ies, HemisphereAndNoRinging) {
  const auto spike = [](double v, double) { return v == 20.0 ? 1000.0 : 0.0; };
  const IesProfile p = parseIes(iesFile(spike, steps(0, 90, 10), {0.0}), "spike.ies");
  EXPECT_EQ(p.intensity(100.0f, 0.0f), 0.0f);
  EXPECT_NEAR(p.intensity(20.0f, 123.0f), 1000.0f, 1e-3f);
  for (float v = 0.0f; v <= 90.0f; v += 0.5f) {
    EXPECT_GE(p.intensity(v, 0.0f), 0.0f) << v;
    EXPECT_LE(p.intensity(v, 0.0f), 1000.0f) << v;
  }
  EXPECT_EQ(p.intensity(45.0f, 0.0f), 0.0f);  // between two zeros
}

// Older editions: no version line (1986) or IESNA91, lumens per lamp, the ballast-lamp factor.
TEST(Ies, OlderEditionsAndRatedLumens) {
  const std::string file =
      "Some luminaire\nTILT=NONE\n2 1500 1.0 3 1 1 1 0.5 0.5 0.2\n0.9 1.1 60\n0 45 90\n0\n"
      "100 80 20\n";
  const IesProfile p = parseIes(file, "old.ies");
  EXPECT_FLOAT_EQ(p.lampLumens, 3000.0f);
  EXPECT_NEAR(p.intensity(0.0f, 0.0f), 100.0f * 0.9f * 1.1f, 1e-3f);
  EXPECT_NEAR(p.intensity(90.0f, 77.0f), 20.0f * 0.9f * 1.1f, 1e-3f);
}

TEST(Ies, BadFilesNameTheLine) {
  const std::string head = "IESNA:LM-63-2002\nTILT=NONE\n";
  const std::pair<std::string, std::string> cases[] = {
      {"IESNA:LM-63-2002\n[TEST] x\n",
       "bad.ies: not an IES photometric file (LM-63): no TILT= line"},
      {"IESNA:LM-63-2002\n[TEST] x\nTILT=INCLUDE\n1\n",
       "bad.ies:3: TILT=INCLUDE is not supported (only TILT=NONE)"},
      {head + "1 -1 1 3 1 2 2 0 0 0\n1 1 0\n",
       "bad.ies:3: type B photometry is not supported (only type C)"},
      {head + "1 -1 1 3 1 1 2 0 0 0\n1 1 0\n0 45 90\n0\n10 20\n",
       "bad.ies:7: the file ends where candela value 3 of horizontal angle 0 should be"},
      {head + "1 -1 1 3 1 1 2 0 0 0\n1 1 0\n0 45 90\n0\n10 x 20\n",
       "bad.ies:7: 'x' is not a number (candela value 2 of horizontal angle 0)"},
      {head + "1 -1 1 3 1 1 2 0 0 0\n1 1 0\n0 90 45\n0\n10 20 30\n",
       "bad.ies:5: vertical angles are not increasing (45 after 90)"},
      {head + "1 -1 1 3 1 1 2 0 0 0\n1 1 0\n0 45 90\n0\n10 -20 30\n",
       "bad.ies:7: a negative candela value (-20)"},
      {head + "1 -1 1 3 1 1 2 0 0 0\n1 1 0\n0 45 90\n0\n10 20 30\n40\n",
       "bad.ies:8: more values than the 1 x 3 candela table"},
      {head + "1 -1 1 3 2 1 2 0 0 0\n1 1 0\n0 45 90\n0 45\n1 2 3 4 5 6\n",
       "bad.ies:6: horizontal angles from 0 to 45: type C files go from 0 to 0, 90, 180 or up to "
       "360, or from 90 to 270"},
      {head + "1 -1 0 3 1 1 2 0 0 0\n1 1 0\n", "bad.ies:3: the candela multiplier is 0"}};
  for (const auto& [text, message] : cases)
    EXPECT_EQ(errorOf([&] { parseIes(text, "bad.ies"); }), message) << text;
  EXPECT_EQ(errorOf([] { readIes("/nonexistent/lamp.ies"); }).rfind("/nonexistent/lamp.ies", 0),
            0u);
}
