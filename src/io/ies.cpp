// IES photometric files (ANSI/IESNA LM-63-2002, "Standard File Format for the Electronic
// Transfer of Photometric Data", and its 1986-1995 editions): the header lines up to TILT=, then
// whitespace- or comma-separated numbers: the lamp and geometry line, the ballast line, the
// vertical angles, the horizontal angles, and the candela values plane by plane.
#include "ibl/io/ies.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"

namespace ibl {

namespace {

// The numbers after the TILT= line, each with the line it is on.
class Numbers {
 public:
  Numbers(std::string_view text, int firstLine, std::string_view name)
      : text_(text), line_(firstLine), name_(name) {}

  [[noreturn]] void failAt(int line, std::string_view problem) const {
    fail(fmt::format("{}:{}", name_, line), problem);
  }

  int line() const { return line_; }

  // The next number, `what` naming it in the error if there is none or it is not a number.
  double next(std::string_view what) {
    skipDelimiters();
    if (at_ >= text_.size())  // named on the line of the last value read
      failAt(lastLine_ ? lastLine_ : line_, fmt::format("the file ends where {} should be", what));
    const std::size_t start = at_;
    while (at_ < text_.size() && !isDelimiter(text_[at_])) ++at_;
    const std::string_view token = text_.substr(start, at_ - start);
    double value = 0.0;
    const char* begin = token.data();
    if (*begin == '+') ++begin;  // from_chars takes no '+'
    const auto [end, ec] = std::from_chars(begin, token.data() + token.size(), value);
    if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(value))
      failAt(line_, fmt::format("'{}' is not a number ({})", token, what));
    lastLine_ = line_;
    return value;
  }

  // The next number, which must be a whole number within [lo, hi].
  int nextInteger(std::string_view what, int lo, int hi) {
    const double v = next(what);
    if (v != std::floor(v) || v < lo || v > hi)
      failAt(lastLine_,
             fmt::format("{} is {}, expected a whole number in [{}, {}]", what, v, lo, hi));
    return static_cast<int>(v);
  }

  int lastLine() const { return lastLine_; }

  // Whether anything but delimiters is left.
  bool atEnd() {
    skipDelimiters();
    return at_ >= text_.size();
  }

 private:
  static bool isDelimiter(char c) {
    return c == ' ' || c == '\t' || c == ',' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
  }
  void skipDelimiters() {
    while (at_ < text_.size() && isDelimiter(text_[at_])) {
      if (text_[at_] == '\n') ++line_;
      ++at_;
    }
  }

  std::string_view text_;
  std::size_t at_ = 0;
  int line_, lastLine_ = 0;
  std::string_view name_;
};

// Angles in degrees, strictly increasing within [lo, hi].
std::vector<float> readAngles(Numbers& in, int count, const char* what, double lo, double hi) {
  std::vector<float> angles;
  for (int i = 0; i < count; ++i) {
    const double a = in.next(what);
    if (a < lo - 1e-6 || a > hi + 1e-6)
      in.failAt(in.lastLine(), fmt::format("{} {} is outside [{}, {}]", what, a, lo, hi));
    if (!angles.empty() && a <= angles.back())
      in.failAt(in.lastLine(),
                fmt::format("{} are not increasing ({} after {})", what, a, angles.back()));
    angles.push_back(static_cast<float>(a));
  }
  return angles;
}

// A cubic through (t0, p0) and (t1, p1) with the finite-difference (Catmull-Rom) tangents of
// the unevenly spaced neighbours t_ and t2, evaluated at x in [t0, t1] and clamped to the range
// of p0 and p1 (no overshoot, nothing negative).
float catmullRomUneven(float t_, float p_, float t0, float p0, float t1, float p1, float t2,
                       float p2, float x) {
  const float h = t1 - t0;
  if (h <= 0.0f) return p0;
  const float m0 = t1 > t_ ? (p1 - p_) / (t1 - t_) : (p1 - p0) / h;
  const float m1 = t2 > t0 ? (p2 - p0) / (t2 - t0) : (p1 - p0) / h;
  const float s = (x - t0) / h, s2 = s * s, s3 = s2 * s;
  const float v = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * h * m0 +
                  (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * h * m1;
  return std::clamp(v, std::min(p0, p1), std::max(p0, p1));
}

// The horizontal planes unfolded over [0, 360) by the file's symmetry: angle and stored plane.
struct Plane {
  float angle;
  int index;
};

std::vector<Plane> unfoldPlanes(const std::vector<float>& h) {
  const int n = static_cast<int>(h.size());
  std::vector<Plane> planes;
  const auto add = [&](float angle, int index) {
    angle = std::fmod(angle + 360.0f, 360.0f);
    planes.push_back({angle, index});
  };
  if (n == 1) return {{0.0f, 0}};
  if (h.front() == 0.0f && h.back() == 90.0f) {  // quadrants
    for (int i = 0; i < n; ++i) add(h[i], i);
    for (int i = n - 2; i >= 0; --i) add(180.0f - h[i], i);
    for (int i = 1; i < n; ++i) add(180.0f + h[i], i);
    for (int i = n - 2; i > 0; --i) add(360.0f - h[i], i);
  } else if (h.front() == 0.0f && h.back() == 180.0f) {  // mirror about the 0-180 plane
    for (int i = 0; i < n; ++i) add(h[i], i);
    for (int i = n - 2; i > 0; --i) add(360.0f - h[i], i);
  } else if (h.front() == 90.0f && h.back() == 270.0f) {  // mirror about the 90-270 plane
    for (int i = 0; i < n; ++i) add(h[i], i);
    for (int i = 0; i < n; ++i) {
      if (h[i] > 90.0f && h[i] <= 180.0f) add(180.0f - h[i], i);
      if (h[i] >= 180.0f && h[i] < 270.0f) add(540.0f - h[i], i);
    }
  } else {  // no symmetry: 0 .. (180, 360], periodic
    for (int i = 0; i < n; ++i)
      if (i < n - 1 || h[i] < 360.0f) add(h[i], i);
  }
  std::sort(planes.begin(), planes.end(),
            [](const Plane& a, const Plane& b) { return a.angle < b.angle; });
  planes.erase(std::unique(planes.begin(), planes.end(),
                           [](const Plane& a, const Plane& b) { return a.angle == b.angle; }),
               planes.end());
  return planes;
}

}  // namespace

float IesProfile::intensity(float verticalDegrees, float horizontalDegrees) const {
  const int nv = static_cast<int>(vertical.size());
  if (nv == 0 || !(verticalDegrees >= vertical.front() && verticalDegrees <= vertical.back()))
    return 0.0f;
  // Along the vertical angles of stored plane `h`.
  const auto alongVertical = [&](int h) {
    const float* c = &candela[static_cast<std::size_t>(h) * nv];
    if (nv == 1) return c[0];
    const int i = std::clamp(
        static_cast<int>(std::upper_bound(vertical.begin(), vertical.end(), verticalDegrees) -
                         vertical.begin()) -
            1,
        0, nv - 2);
    const int a = std::max(i - 1, 0), d = std::min(i + 2, nv - 1);
    return catmullRomUneven(vertical[a], c[a], vertical[i], c[i], vertical[i + 1], c[i + 1],
                            vertical[d], c[d], verticalDegrees);
  };
  const int np = static_cast<int>(planeAngles.size());
  if (np <= 1) return alongVertical(np == 1 ? planeOf[0] : 0);
  const float phi = std::fmod(std::fmod(horizontalDegrees, 360.0f) + 360.0f, 360.0f);
  int i = static_cast<int>(std::upper_bound(planeAngles.begin(), planeAngles.end(), phi) -
                           planeAngles.begin()) -
          1;
  if (i < 0) i = np - 1;  // phi before the first plane: the interval from the last
  // The four planes around phi, with their angles unwrapped to increase through it.
  float t[4], p[4];
  for (int k = -1; k <= 2; ++k) {
    const int j = i + k;
    const int wrapped = ((j % np) + np) % np;
    t[k + 1] = planeAngles[wrapped] + 360.0f * static_cast<float>((j - wrapped) / np);
    p[k + 1] = alongVertical(planeOf[wrapped]);
  }
  const float x = phi < t[1] ? phi + 360.0f : phi;
  return catmullRomUneven(t[0], p[0], t[1], p[1], t[2], p[2], t[3], p[3], x);
}

float IesProfile::maxCandela() const {
  return candela.empty() ? 0.0f : *std::max_element(candela.begin(), candela.end());
}

double IesProfile::flux() const {
  constexpr double kDeg = std::numbers::pi / 180.0;
  constexpr int kVerticalSteps = 720, kHorizontalSteps = 360;
  const bool symmetric = horizontal.size() == 1;
  double sum = 0.0;
  for (int a = 0; a < kVerticalSteps; ++a) {
    const double theta = (a + 0.5) * 180.0 / kVerticalSteps;
    const double band =
        (std::cos((theta - 90.0 / kVerticalSteps) * kDeg) -
         std::cos((theta + 90.0 / kVerticalSteps) * kDeg));  // its solid angle / dphi
    double ring = 0.0;
    if (symmetric) {
      ring = intensity(static_cast<float>(theta), 0.0f) * 2.0 * std::numbers::pi;
    } else {
      for (int b = 0; b < kHorizontalSteps; ++b)
        ring += intensity(static_cast<float>(theta),
                          static_cast<float>((b + 0.5) * 360.0 / kHorizontalSteps));
      ring *= 2.0 * std::numbers::pi / kHorizontalSteps;
    }
    sum += ring * band;
  }
  return sum;
}

IesProfile parseIes(std::string_view text, std::string_view name) {
  // The header: label and keyword lines, up to the line that starts with TILT=.
  int line = 1;
  std::size_t at = 0;
  std::string tilt;
  bool foundTilt = false;
  while (at < text.size()) {
    std::size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    std::string_view l = text.substr(at, end - at);
    while (!l.empty() && (l.front() == ' ' || l.front() == '\t')) l.remove_prefix(1);
    while (!l.empty() && (l.back() == '\r' || l.back() == ' ' || l.back() == '\t'))
      l.remove_suffix(1);
    at = end + 1;
    if (l.substr(0, 5) == "TILT=") {
      tilt = std::string(l.substr(5));
      foundTilt = true;
      break;
    }
    ++line;
  }
  if (!foundTilt) fail(name, "not an IES photometric file (LM-63): no TILT= line");
  if (tilt != "NONE")
    fail(fmt::format("{}:{}", name, line),
         fmt::format("TILT={} is not supported (only TILT=NONE)", tilt));
  Numbers in(at < text.size() ? text.substr(at) : std::string_view(), line + 1, name);
  const int lamps = in.nextInteger("the number of lamps", 1, 1000000);
  const double lumensPerLamp = in.next("the lumens per lamp");
  if (lumensPerLamp <= 0.0 && lumensPerLamp != -1.0)
    in.failAt(in.lastLine(),
              fmt::format("lumens per lamp is {} (positive, or -1 for absolute photometry)",
                          lumensPerLamp));
  const double multiplier = in.next("the candela multiplier");
  if (multiplier <= 0.0)
    in.failAt(in.lastLine(), fmt::format("the candela multiplier is {}", multiplier));
  const int nv = in.nextInteger("the number of vertical angles", 1, 100000);
  const int nh = in.nextInteger("the number of horizontal angles", 1, 100000);
  if (static_cast<long long>(nv) * nh > 10'000'000)
    in.failAt(in.lastLine(), fmt::format("a web of {} x {} angles is too large", nh, nv));
  const int type = in.nextInteger("the photometric type", 1, 3);
  if (type != 1)
    in.failAt(in.lastLine(), fmt::format("type {} photometry is not supported (only type C)",
                                         type == 2 ? "B" : "A"));
  in.nextInteger("the units type", 1, 2);
  for (const char* what : {"the width", "the length", "the height"}) in.next(what);
  const double ballast = in.next("the ballast factor");
  const double ballastLamp = in.next("the ballast-lamp photometric factor");
  in.next("the input watts");
  if (ballast <= 0.0) in.failAt(in.lastLine(), fmt::format("the ballast factor is {}", ballast));
  IesProfile p;
  p.lampLumens = lumensPerLamp < 0.0 ? -1.0f : static_cast<float>(lamps * lumensPerLamp);
  p.vertical = readAngles(in, nv, "vertical angles", 0.0, 180.0);
  p.horizontal = readAngles(in, nh, "horizontal angles", 0.0, 360.0);
  const float h0 = p.horizontal.front(), h1 = p.horizontal.back();
  const bool valid =
      nh == 1 ? h0 == 0.0f
              : (h0 == 0.0f && (h1 == 90.0f || h1 >= 180.0f)) || (h0 == 90.0f && h1 == 270.0f);
  if (!valid)
    in.failAt(in.lastLine(),
              fmt::format("horizontal angles from {} to {}: type C files go from 0 to 0, 90, 180 "
                          "or up to 360, or from 90 to 270",
                          h0, h1));
  // LM-63-2002 calls the second ballast value "future use" (1); earlier editions multiply by it.
  const double scale = multiplier * ballast * (ballastLamp > 0.0 ? ballastLamp : 1.0);
  p.candela.reserve(static_cast<std::size_t>(nv) * nh);
  for (int h = 0; h < nh; ++h)
    for (int v = 0; v < nv; ++v) {
      const double c =
          in.next(fmt::format("candela value {} of horizontal angle {}", v + 1, p.horizontal[h]));
      if (c < 0.0) in.failAt(in.lastLine(), fmt::format("a negative candela value ({})", c));
      p.candela.push_back(static_cast<float>(c * scale));
    }
  if (!in.atEnd())
    in.failAt(in.line(), fmt::format("more values than the {} x {} candela table", nh, nv));
  for (const Plane& plane : unfoldPlanes(p.horizontal)) {
    p.planeAngles.push_back(plane.angle);
    p.planeOf.push_back(plane.index);
  }
  return p;
}

IesProfile readIes(const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  return parseIes(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                  path.string());
}

}  // namespace ibl
