// Radiance RGBE (.hdr / .pic): Greg Ward, "Real Pixels" (Graphics Gems II) and the Radiance
// file format documentation. Flat, old-style and new-style run-length encoded scanlines; all
// eight orientations of the resolution string.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/core/version.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/pixel_formats.hpp"

namespace ibl {

namespace {

glm::vec3 rgbeToFloat(const std::uint8_t* p) {
  if (p[3] == 0) return glm::vec3(0.0f);
  const float scale = std::ldexp(1.0f, static_cast<int>(p[3]) - (128 + 8));
  return {(static_cast<float>(p[0]) + 0.5f) * scale, (static_cast<float>(p[1]) + 0.5f) * scale,
          (static_cast<float>(p[2]) + 0.5f) * scale};
}

void floatToRgbe(glm::vec3 value, std::uint8_t* p) {
  const glm::vec3 c = representable(PixelFormat::Rgba32f, value);  // no infinity or NaN
  const float m = std::max({c.x, c.y, c.z});
  if (!(m > 1e-32f)) {
    p[0] = p[1] = p[2] = p[3] = 0;
    return;
  }
  int e;
  const float scale = std::frexp(m, &e) * 256.0f / m;
  const auto comp = [&](float v) {
    return static_cast<std::uint8_t>(std::clamp(v * scale, 0.0f, 255.0f));
  };
  p[0] = comp(c.x);
  p[1] = comp(c.y);
  p[2] = comp(c.z);
  p[3] = static_cast<std::uint8_t>(std::clamp(e + 128, 0, 255));
}

class Reader {
 public:
  Reader(std::span<const std::uint8_t> b, std::string_view name) : bytes_(b), name_(name) {}
  bool atEnd() const { return pos_ >= bytes_.size(); }
  std::uint8_t byte() {
    if (atEnd()) fail(name_, "truncated pixel data");
    return bytes_[pos_++];
  }
  std::string line() {
    std::string s;
    while (true) {
      if (atEnd()) fail(name_, "truncated header");
      const char c = static_cast<char>(bytes_[pos_++]);
      if (c == '\n') return s;
      if (s.size() > 4096) fail(name_, "header line too long (not a Radiance file?)");
      s += c;
    }
  }
  std::size_t pos_ = 0;

 private:
  std::span<const std::uint8_t> bytes_;
  std::string_view name_;
};

// Reads one scanline of `len` RGBE pixels into `out` (4 bytes a pixel).
void readScanline(Reader& in, std::string_view name, int len, std::uint8_t* out) {
  const std::size_t start = in.pos_;
  if (len >= 8 && len <= 0x7fff) {
    const std::uint8_t b0 = in.byte(), b1 = in.byte(), b2 = in.byte(), b3 = in.byte();
    if (b0 == 2 && b1 == 2 && (b2 & 0x80) == 0) {
      if (((b2 << 8) | b3) != len) fail(name, "corrupt run-length encoded scanline (bad length)");
      for (int c = 0; c < 4; ++c) {
        int x = 0;
        while (x < len) {
          int count = in.byte();
          if (count > 128) {
            count -= 128;
            if (x + count > len) fail(name, "corrupt run-length encoded scanline (run too long)");
            const std::uint8_t v = in.byte();
            for (int i = 0; i < count; ++i) out[4 * (x++) + c] = v;
          } else {
            if (count == 0 || x + count > len)
              fail(name, "corrupt run-length encoded scanline (bad literal count)");
            for (int i = 0; i < count; ++i) out[4 * (x++) + c] = in.byte();
          }
        }
      }
      return;
    }
    in.pos_ = start;  // not new-style RLE: flat or old-style
  }
  int x = 0, shift = 0;
  while (x < len) {
    std::uint8_t p[4] = {in.byte(), in.byte(), in.byte(), in.byte()};
    if (p[0] == 1 && p[1] == 1 && p[2] == 1) {  // old-style run: repeat the previous pixel
      if (x == 0) fail(name, "corrupt scanline (run without a preceding pixel)");
      if (shift > 16) fail(name, "corrupt scanline (run length overflow)");
      const long count = static_cast<long>(p[3]) << shift;
      if (x + count > len) fail(name, "corrupt scanline (run too long)");
      for (long i = 0; i < count; ++i, ++x) std::memcpy(out + 4 * x, out + 4 * (x - 1), 4);
      shift += 8;
    } else {
      std::memcpy(out + 4 * (x++), p, 4);
      shift = 0;
    }
  }
}

struct Axis {
  char sign;  // '+' or '-'
  char name;  // 'X' or 'Y'
  long count;
};

}  // namespace

Image decodeHdr(std::span<const std::uint8_t> bytes, std::string_view name) {
  Reader in(bytes, name);
  const std::string magic = in.line();
  if (magic.rfind("#?", 0) != 0) fail(name, "not a Radiance HDR file (no #? signature)");
  for (int lines = 0;; ++lines) {
    if (lines > 1000) fail(name, "header too long");
    const std::string l = in.line();
    if (l.empty()) break;
    if (l.rfind("FORMAT=", 0) == 0) {
      const std::string fmtName = l.substr(7);
      if (fmtName == "32-bit_rle_xyze")
        fail(name, "XYZE Radiance files are not supported (only 32-bit_rle_rgbe)");
      if (fmtName != "32-bit_rle_rgbe") fail(name, fmt::format("unknown FORMAT '{}'", fmtName));
    }
  }
  // Resolution string, e.g. "-Y 512 +X 1024": the first axis is the slow one.
  const std::string res = in.line();
  Axis a{}, b{};
  char sa[3] = {}, sb[3] = {};
  if (std::sscanf(res.c_str(), "%2s %ld %2s %ld", sa, &a.count, sb, &b.count) != 4 ||
      (sa[0] != '+' && sa[0] != '-') || (sb[0] != '+' && sb[0] != '-') ||
      (sa[1] != 'X' && sa[1] != 'Y') || (sb[1] != 'X' && sb[1] != 'Y') || sa[1] == sb[1])
    fail(name, fmt::format("bad resolution string '{}'", res.substr(0, 40)));
  a.sign = sa[0];
  a.name = sa[1];
  b.sign = sb[0];
  b.name = sb[1];
  if (a.count <= 0 || b.count <= 0) fail(name, "bad image size in the resolution string");
  const long width = a.name == 'X' ? a.count : b.count;
  const long height = a.name == 'Y' ? a.count : b.count;
  checkImageSize(name, static_cast<std::uint64_t>(width), static_cast<std::uint64_t>(height));
  // Every scanline takes at least 4 bytes: reject truncated files before allocating.
  if (static_cast<std::uint64_t>(a.count) * 4 > bytes.size() - in.pos_)
    fail(name, "truncated pixel data");

  Image img(static_cast<int>(width), static_cast<int>(height));
  std::vector<std::uint8_t> scan(static_cast<std::size_t>(b.count) * 4);
  // Image coordinate of the k-th position along an axis (Radiance: +Y points up, +X right).
  const auto coord = [&](const Axis& ax, long k) {
    const long n = ax.name == 'X' ? width : height;
    const bool forward = (ax.name == 'X') == (ax.sign == '+');
    return static_cast<int>(forward ? k : n - 1 - k);
  };
  for (long i = 0; i < a.count; ++i) {
    readScanline(in, name, static_cast<int>(b.count), scan.data());
    const int ca = coord(a, i);
    for (long j = 0; j < b.count; ++j) {
      const int cb = coord(b, j);
      const int x = a.name == 'X' ? ca : cb, y = a.name == 'Y' ? ca : cb;
      img.at(x, y) = rgbeToFloat(&scan[4 * j]);
    }
  }
  return img;
}

namespace {
void appendRunLengthEncoded(std::vector<std::uint8_t>& out, const std::uint8_t* d, int len) {
  const auto runAt = [&](int i) {
    int r = 1;
    while (i + r < len && r < 127 && d[i + r] == d[i]) ++r;
    return r;
  };
  int i = 0;
  while (i < len) {
    const int run = runAt(i);
    if (run >= 4) {
      out.push_back(static_cast<std::uint8_t>(128 + run));
      out.push_back(d[i]);
      i += run;
      continue;
    }
    const int start = i;
    while (i < len && i - start < 128 && runAt(i) < 4) ++i;
    out.push_back(static_cast<std::uint8_t>(i - start));
    out.insert(out.end(), d + start, d + i);
  }
}
}  // namespace

std::vector<std::uint8_t> encodeHdr(const Image& img) {
  const std::string header =
      fmt::format("#?RADIANCE\n# Written by ibl {}\nFORMAT=32-bit_rle_rgbe\n\n-Y {} +X {}\n",
                  kVersion, img.height, img.width);
  std::vector<std::uint8_t> out(header.begin(), header.end());
  const int w = img.width;
  const bool rle = w >= 8 && w <= 0x7fff;
  std::vector<std::uint8_t> rgbe(static_cast<std::size_t>(w) * 4);
  std::vector<std::uint8_t> plane(w);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < w; ++x) floatToRgbe(img.at(x, y), &rgbe[4 * x]);
    if (!rle) {
      out.insert(out.end(), rgbe.begin(), rgbe.end());
      continue;
    }
    out.insert(out.end(),
               {2, 2, static_cast<std::uint8_t>(w >> 8), static_cast<std::uint8_t>(w & 255)});
    for (int c = 0; c < 4; ++c) {
      for (int x = 0; x < w; ++x) plane[x] = rgbe[4 * x + c];
      appendRunLengthEncoded(out, plane.data(), w);
    }
  }
  return out;
}

}  // namespace ibl
