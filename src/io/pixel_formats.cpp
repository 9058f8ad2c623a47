#include "ibl/io/pixel_formats.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace ibl {

std::uint32_t bytesPerTexel(PixelFormat f) {
  switch (f) {
    case PixelFormat::Rgba16f:
      return 8;
    case PixelFormat::Rgba32f:
      return 16;
    case PixelFormat::B10G11R11:
    case PixelFormat::E5B9G9R9:
      return 4;
  }
  return 0;
}

glm::vec3 largestValue(PixelFormat f) {
  switch (f) {
    case PixelFormat::Rgba16f:
      return glm::vec3(kMaxHalf);
    case PixelFormat::Rgba32f:
      return glm::vec3(std::numeric_limits<float>::max());
    case PixelFormat::B10G11R11:
      return {kMaxB10G11R11, kMaxB10G11R11, kMaxB10};
    case PixelFormat::E5B9G9R9:
      return glm::vec3(kMaxE5B9G9R9);
  }
  return glm::vec3(0.0f);
}

glm::vec3 representable(PixelFormat f, glm::vec3 c) {
  const glm::vec3 hi = largestValue(f);
  const bool isSigned = f == PixelFormat::Rgba16f || f == PixelFormat::Rgba32f;
  glm::vec3 out;
  for (int i = 0; i < 3; ++i)
    out[i] = std::isnan(c[i]) ? 0.0f : std::clamp(c[i], isSigned ? -hi[i] : 0.0f, hi[i]);
  return out;
}

std::uint32_t ktxTypeSize(PixelFormat f) {
  // KTX2: the size of the data type of a component; 1 for packed formats would be wrong,
  // packed formats use the size of the packed word.
  switch (f) {
    case PixelFormat::Rgba16f:
      return 2;
    case PixelFormat::Rgba32f:
      return 4;
    case PixelFormat::B10G11R11:
    case PixelFormat::E5B9G9R9:
      return 4;
  }
  return 0;
}

std::string_view formatName(PixelFormat f) {
  switch (f) {
    case PixelFormat::Rgba16f:
      return "rgba16f";
    case PixelFormat::Rgba32f:
      return "rgba32f";
    case PixelFormat::B10G11R11:
      return "b10g11r11";
    case PixelFormat::E5B9G9R9:
      return "e5b9g9r9";
  }
  return "?";
}

std::string_view vulkanFormatName(PixelFormat f) {
  switch (f) {
    case PixelFormat::Rgba16f:
      return "VK_FORMAT_R16G16B16A16_SFLOAT";
    case PixelFormat::Rgba32f:
      return "VK_FORMAT_R32G32B32A32_SFLOAT";
    case PixelFormat::B10G11R11:
      return "VK_FORMAT_B10G11R11_UFLOAT_PACK32";
    case PixelFormat::E5B9G9R9:
      return "VK_FORMAT_E5B9G9R9_UFLOAT_PACK32";
  }
  return "?";
}

std::optional<PixelFormat> parsePixelFormat(std::string_view name) {
  for (auto f :
       {PixelFormat::Rgba16f, PixelFormat::Rgba32f, PixelFormat::B10G11R11, PixelFormat::E5B9G9R9})
    if (name == formatName(f)) return f;
  return std::nullopt;
}

std::optional<PixelFormat> pixelFormatFromVk(std::uint32_t vk) {
  switch (vk) {
    case 97:
      return PixelFormat::Rgba16f;
    case 109:
      return PixelFormat::Rgba32f;
    case 122:
      return PixelFormat::B10G11R11;
    case 123:
      return PixelFormat::E5B9G9R9;
    default:
      return std::nullopt;
  }
}

std::uint16_t floatToHalf(float v) {
  std::uint32_t x;
  std::memcpy(&x, &v, 4);
  const std::uint32_t sign = (x >> 16) & 0x8000u;
  x &= 0x7fffffffu;
  if (x > 0x7f800000u) return static_cast<std::uint16_t>(sign | 0x7e00u);   // NaN
  if (x >= 0x477ff000u) return static_cast<std::uint16_t>(sign | 0x7c00u);  // overflow -> inf
  if (x < 0x38800000u) {  // subnormal half (or zero): value * 2^24, rounded to nearest even
    float a;
    std::memcpy(&a, &x, 4);
    const float scaled = a * 16777216.0f;
    return static_cast<std::uint16_t>(sign | static_cast<std::uint32_t>(std::nearbyint(scaled)));
  }
  // Normal: rebias the exponent, round the 13 dropped mantissa bits to nearest even.
  const std::uint32_t rounded = x + 0x0fffu + ((x >> 13) & 1u);
  return static_cast<std::uint16_t>(sign | ((rounded - 0x38000000u) >> 13));
}

float halfToFloat(std::uint16_t h) {
  const std::uint32_t sign = static_cast<std::uint32_t>(h & 0x8000u) << 16;
  const std::uint32_t exp = (h >> 10) & 0x1fu;
  const std::uint32_t mant = h & 0x3ffu;
  float out;
  if (exp == 0) {
    out = std::ldexp(static_cast<float>(mant), -24);
    return sign ? -out : out;
  }
  std::uint32_t bits;
  if (exp == 31) {
    bits = sign | 0x7f800000u | (mant << 13);
  } else {
    bits = sign | ((exp + 112u) << 23) | (mant << 13);
  }
  std::memcpy(&out, &bits, 4);
  return out;
}

namespace {

// Unsigned float with a 5-bit exponent (bias 15) and `m` mantissa bits, round to nearest.
std::uint32_t packUnsignedFloat(float v, int m) {
  if (!(v > 0.0f)) return 0;  // zero, negative, NaN
  const float maxValue = std::ldexp(2.0f - std::ldexp(1.0f, -m), 15);
  v = std::min(v, maxValue);
  int e;
  const float frac = std::frexp(v, &e);  // v = frac * 2^e, frac in [0.5, 1)
  int biased = e - 1 + 15;
  const std::uint32_t one = 1u << m;
  if (biased <= 0) {  // subnormal: v = mant / 2^m * 2^-14
    const auto mant = static_cast<std::uint32_t>(std::lround(std::ldexp(v, 14 + m)));
    return mant;  // mant == one rounds up into the smallest normal, which has the same bits
  }
  auto mant =
      static_cast<std::uint32_t>(std::lround((2.0f * frac - 1.0f) * static_cast<float>(one)));
  if (mant == one) {
    mant = 0;
    ++biased;
  }
  if (biased > 30) return (30u << m) | (one - 1);
  return (static_cast<std::uint32_t>(biased) << m) | mant;
}

float unpackUnsignedFloat(std::uint32_t bits, int m) {
  const std::uint32_t exp = bits >> m;
  const std::uint32_t mant = bits & ((1u << m) - 1);
  if (exp == 0) return std::ldexp(static_cast<float>(mant), -14 - m);
  if (exp == 31) return mant ? std::nanf("") : INFINITY;
  return std::ldexp(1.0f + static_cast<float>(mant) / static_cast<float>(1u << m),
                    static_cast<int>(exp) - 15);
}

}  // namespace

std::uint32_t packB10G11R11(glm::vec3 c) {
  return packUnsignedFloat(c.x, 6) | (packUnsignedFloat(c.y, 6) << 11) |
         (packUnsignedFloat(c.z, 5) << 22);
}

glm::vec3 unpackB10G11R11(std::uint32_t p) {
  return {unpackUnsignedFloat(p & 0x7ffu, 6), unpackUnsignedFloat((p >> 11) & 0x7ffu, 6),
          unpackUnsignedFloat(p >> 22, 5)};
}

// EXT_texture_shared_exponent, "Encoding" section: N = 9 mantissa bits, B = 15, Emax = 31.
std::uint32_t packE5B9G9R9(glm::vec3 c) {
  constexpr int kN = 9, kB = 15;
  const auto clampComponent = [](float v) { return v > 0.0f ? std::min(v, kMaxE5B9G9R9) : 0.0f; };
  const float r = clampComponent(c.x), g = clampComponent(c.y), b = clampComponent(c.z);
  const float maxc = std::max({r, g, b});
  int floorLog2 = -kB - 1;
  if (maxc > 0.0f) {
    int e;
    std::frexp(maxc, &e);
    floorLog2 = std::max(-kB - 1, e - 1);
  }
  int expShared = floorLog2 + 1 + kB;
  float scale = std::ldexp(1.0f, -(expShared - kB - kN));
  if (static_cast<int>(std::floor(maxc * scale + 0.5f)) == (1 << kN)) {
    ++expShared;
    scale *= 0.5f;
  }
  const auto mant = [&](float v) {
    return static_cast<std::uint32_t>(std::floor(v * scale + 0.5f));
  };
  return mant(r) | (mant(g) << 9) | (mant(b) << 18) | (static_cast<std::uint32_t>(expShared) << 27);
}

glm::vec3 unpackE5B9G9R9(std::uint32_t p) {
  const int exponent = static_cast<int>(p >> 27) - 15 - 9;
  return {std::ldexp(static_cast<float>(p & 0x1ffu), exponent),
          std::ldexp(static_cast<float>((p >> 9) & 0x1ffu), exponent),
          std::ldexp(static_cast<float>((p >> 18) & 0x1ffu), exponent)};
}

void encodeTexel(PixelFormat f, glm::vec3 value, std::uint8_t* dst) {
  const glm::vec3 c = representable(f, value);  // no infinity or NaN in any file
  switch (f) {
    case PixelFormat::Rgba16f: {
      const std::uint16_t h[4] = {floatToHalf(c.x), floatToHalf(c.y), floatToHalf(c.z), 0x3C00};
      std::memcpy(dst, h, 8);
      return;
    }
    case PixelFormat::Rgba32f: {
      const float v[4] = {c.x, c.y, c.z, 1.0f};
      std::memcpy(dst, v, 16);
      return;
    }
    case PixelFormat::B10G11R11: {
      const std::uint32_t p = packB10G11R11(c);
      std::memcpy(dst, &p, 4);
      return;
    }
    case PixelFormat::E5B9G9R9: {
      const std::uint32_t p = packE5B9G9R9(c);
      std::memcpy(dst, &p, 4);
      return;
    }
  }
}

glm::vec3 decodeTexel(PixelFormat f, const std::uint8_t* src) {
  switch (f) {
    case PixelFormat::Rgba16f: {
      std::uint16_t h[3];
      std::memcpy(h, src, 6);
      return {halfToFloat(h[0]), halfToFloat(h[1]), halfToFloat(h[2])};
    }
    case PixelFormat::Rgba32f: {
      float v[3];
      std::memcpy(v, src, 12);
      return {v[0], v[1], v[2]};
    }
    case PixelFormat::B10G11R11: {
      std::uint32_t p;
      std::memcpy(&p, src, 4);
      return unpackB10G11R11(p);
    }
    case PixelFormat::E5B9G9R9: {
      std::uint32_t p;
      std::memcpy(&p, src, 4);
      return unpackE5B9G9R9(p);
    }
  }
  return glm::vec3(0.0f);
}

}  // namespace ibl
