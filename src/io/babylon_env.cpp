// Babylon.js's .env container (include/ibl/io/babylon_env.hpp; docs/targets.md, "Babylon.js").
#include "ibl/io/babylon_env.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>

#include <fmt/format.h>
#include <stb_image.h>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/io/image_io.hpp"

namespace ibl {

namespace {

using Json = nlohmann::ordered_json;

constexpr float kGamma = 2.2f;  // Babylon's toGammaSpace / toLinearSpace use the 2.2 power
constexpr const char* kPolynomialKeys[9] = {"x", "y", "z", "xx", "yy", "zz", "yz", "zx", "xy"};
constexpr int kFaces = 6;

int levelCountOf(int width) {
  return std::countr_zero(static_cast<unsigned>(width)) + 1;
}

}  // namespace

std::array<std::uint8_t, 4> toRgbd(glm::vec3 c) {
  // rgbdEncode: D = clamp(floor(max(255 / max(rgb), 1)) / 255, 0, 1), rgb' = (rgb D)^(1/2.2).
  const float maxRgb = std::max({c.x, c.y, c.z, 1e-7f});
  const float steps = std::floor(std::max(kRgbdMaxRange / maxRgb, 1.0f));
  const float d = std::min(steps, 255.0f) / 255.0f;
  std::array<std::uint8_t, 4> out{};
  for (int i = 0; i < 3; ++i) {
    const float v = std::pow(std::clamp(c[i] * d, 0.0f, 1.0f), 1.0f / kGamma);
    out[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(std::lround(255.0f * v));
  }
  out[3] = static_cast<std::uint8_t>(std::lround(255.0f * d));
  return out;
}

glm::vec3 fromRgbd(std::array<std::uint8_t, 4> b) {
  // rgbdDecode: rgb = rgb'^2.2 / D.
  const float d = std::max<float>(b[3], 1.0f) / 255.0f;
  glm::vec3 c;
  for (int i = 0; i < 3; ++i) c[i] = std::pow(b[static_cast<std::size_t>(i)] / 255.0f, kGamma) / d;
  return c;
}

std::vector<std::uint8_t> encodeBabylonEnv(const BabylonEnvironment& env) {
  const int width = env.width;
  if (width < 1 || !std::has_single_bit(static_cast<unsigned>(width)))
    fail("env", fmt::format("the cube's width {} is not a power of two", width));
  const int levels = levelCountOf(width);
  if (static_cast<int>(env.levels.size()) != levels)
    fail("env", fmt::format("{} levels given, a {}^2 cube has {} (down to 1^2)", env.levels.size(),
                            width, levels));
  std::vector<std::vector<std::uint8_t>> pngs;
  for (int m = 0; m < levels; ++m) {
    const int n = width >> m;
    if (env.levels[m].size() != kFaces) fail("env", fmt::format("level {} is not 6 faces", m));
    for (const Image& face : env.levels[m]) {
      if (face.width != n || face.height != n)
        fail("env",
             fmt::format("level {} is {}x{}, expected {}x{}", m, face.width, face.height, n, n));
      // Bottom row first: Babylon uploads the PNG flipped, so that its last row is row 0.
      std::vector<std::uint8_t> rgba(static_cast<std::size_t>(n) * n * 4);
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const auto px = toRgbd(face.at(x, n - 1 - y));
          std::memcpy(&rgba[(static_cast<std::size_t>(y) * n + x) * 4], px.data(), 4);
        }
      pngs.push_back(encodePng8(n, n, 4, rgba));
    }
  }
  Json manifest;
  manifest["version"] = 2;
  manifest["width"] = width;
  manifest["imageType"] = "image/png";
  Json irradiance;
  for (int k = 0; k < 9; ++k) {
    const glm::vec3 c = env.polynomial[static_cast<std::size_t>(k)];
    irradiance[kPolynomialKeys[k]] = {c.x, c.y, c.z};
  }
  manifest["irradiance"] = irradiance;
  Json mipmaps = Json::array();
  std::size_t position = 0;
  for (const auto& png : pngs) {
    mipmaps.push_back({{"length", png.size()}, {"position", position}});
    position += png.size();
  }
  manifest["specular"] = {{"mipmaps", mipmaps}, {"lodGenerationScale", env.lodGenerationScale}};
  const std::string text = manifest.dump();

  std::vector<std::uint8_t> out(sizeof kBabylonEnvMagic + text.size() + 1 + position);
  std::memcpy(out.data(), kBabylonEnvMagic, sizeof kBabylonEnvMagic);
  std::memcpy(out.data() + sizeof kBabylonEnvMagic, text.data(), text.size());
  std::size_t at = sizeof kBabylonEnvMagic + text.size() + 1;  // past the 0 byte
  for (const auto& png : pngs) {
    std::memcpy(out.data() + at, png.data(), png.size());
    at += png.size();
  }
  return out;
}

namespace {

// One face's PNG, decoded: an n x n RGBA image whose rows are stored bottom first.
Image decodeRgbdFace(std::span<const std::uint8_t> png, int n, std::string_view name, int level,
                     int face) {
  const auto where = [&](std::string_view what) {
    fail(name, fmt::format("level {} face {}: {}", level, face, what));
  };
  if (png.size() > static_cast<std::size_t>(INT32_MAX)) where("image too large");
  const int len = static_cast<int>(png.size());
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(png.data(), len, &w, &h, &comp)) where("not a PNG image");
  if (w != n || h != n) where(fmt::format("is {}x{}, expected {}x{}", w, h, n, n));
  stbi_uc* px = stbi_load_from_memory(png.data(), len, &w, &h, &comp, 4);
  if (!px) where("corrupt PNG image");
  Image img(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      std::array<std::uint8_t, 4> b{};
      std::memcpy(b.data(), px + (static_cast<std::size_t>(y) * n + x) * 4, 4);
      img.at(x, n - 1 - y) = fromRgbd(b);
    }
  stbi_image_free(px);
  return img;
}

}  // namespace

BabylonEnvironment decodeBabylonEnv(std::span<const std::uint8_t> b, std::string_view name) {
  if (b.size() < 8 || std::memcmp(b.data(), kBabylonEnvMagic, 8) != 0)
    fail(name, "not a Babylon.js environment (.env) file: bad magic bytes");
  const auto end = std::find(b.begin() + 8, b.end(), std::uint8_t{0});
  if (end == b.end()) fail(name, "truncated: the JSON manifest has no terminating 0 byte");
  const std::size_t dataStart = static_cast<std::size_t>(end - b.begin()) + 1;
  Json manifest;
  try {
    manifest = Json::parse(b.begin() + 8, end);
  } catch (const Json::exception& e) {
    fail(name, fmt::format("corrupt JSON manifest: {}", e.what()));
  }
  BabylonEnvironment env;
  try {
    const int version = manifest.at("version").get<int>();
    if (version != 1 && version != 2)
      fail(name, fmt::format("unsupported .env version {} (1 and 2 are read)", version));
    if (version == 2 && manifest.value("imageType", std::string("image/png")) != "image/png")
      fail(name, fmt::format("faces stored as {}: only image/png is read",
                             manifest.at("imageType").get<std::string>()));
    const std::int64_t width = manifest.at("width").get<std::int64_t>();
    if (width < 1 || width > (1 << 16) || !std::has_single_bit(static_cast<std::uint64_t>(width)))
      fail(name, fmt::format("cube width {} is not a power of two up to 65536", width));
    checkImageSize(name, static_cast<std::uint64_t>(width), static_cast<std::uint64_t>(width));
    env.width = static_cast<int>(width);
    if (manifest.contains("irradiance") && !manifest["irradiance"].is_null())
      for (int k = 0; k < 9; ++k) {
        const auto c = manifest["irradiance"].at(kPolynomialKeys[k]).get<std::vector<float>>();
        if (c.size() != 3)
          fail(name, fmt::format("irradiance.{} is not 3 numbers", kPolynomialKeys[k]));
        env.polynomial[static_cast<std::size_t>(k)] = {c[0], c[1], c[2]};
      }
    const Json& specular = manifest.at("specular");
    env.lodGenerationScale = specular.value("lodGenerationScale", 0.8f);
    if (!(env.lodGenerationScale > 0.0f)) env.lodGenerationScale = 0.8f;  // Babylon's fallback
    const Json& mipmaps = specular.at("mipmaps");
    const int levels = levelCountOf(env.width);
    if (!mipmaps.is_array() || mipmaps.size() != static_cast<std::size_t>(6 * levels))
      fail(name, fmt::format("specular.mipmaps holds {} images, a {}^2 cube needs {}",
                             mipmaps.is_array() ? mipmaps.size() : 0, env.width, 6 * levels));
    const std::size_t payload = b.size() - dataStart;
    env.levels.resize(static_cast<std::size_t>(levels));
    for (int m = 0; m < levels; ++m)
      for (int face = 0; face < kFaces; ++face) {
        const Json& image = mipmaps[static_cast<std::size_t>(6 * m + face)];
        const std::uint64_t position = image.at("position").get<std::uint64_t>();
        const std::uint64_t length = image.at("length").get<std::uint64_t>();
        if (position > payload || length > payload - position)
          fail(name,
               fmt::format("truncated: level {} face {} lies past the end of the file", m, face));
        env.levels[static_cast<std::size_t>(m)].push_back(
            decodeRgbdFace(b.subspan(dataStart + position, length), env.width >> m, name, m, face));
      }
  } catch (const Json::exception& e) {
    fail(name, fmt::format("bad manifest: {}", e.what()));
  }
  return env;
}

}  // namespace ibl
