// Images and textures: each image's bytes (a buffer view, a data URI or a file), its header
// probed against its size, decoded once to 8-bit RGBA within the texel limit; the samplers.
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <limits>

#include <fmt/format.h>
#include <stb_image.h>
#include <webp/decode.h>

#include "document.hpp"
#include "ibl/io/file_io.hpp"
#include "io/text_codecs.hpp"

namespace ibl::gltf {

namespace {

namespace fs = std::filesystem;

std::uint32_t readBe32(const std::uint8_t* p) {
  return (static_cast<std::uint32_t>(p[0]) << 24) | (p[1] << 16) | (p[2] << 8) | p[3];
}

// Whether the bytes are a WebP file: a RIFF container of form type WEBP.
bool isWebp(std::span<const std::uint8_t> b) {
  return b.size() >= 12 && std::memcmp(b.data(), "RIFF", 4) == 0 &&
         std::memcmp(b.data() + 8, "WEBP", 4) == 0;
}

// Whether an image of `kind` ("PNG", ...) and w x h pixels is within ibl's limits; if not,
// r.problem says why.
bool withinPixelLimits(const char* kind, u64 w, u64 h, ImageProbe& r) {
  if (w > 0 && h > 0 && w <= kMaxImageDimension && h <= kMaxImageDimension &&
      w * h <= kMaxImagePixels)
    return true;
  r.problem = fmt::format("a {} of {}x{} pixels (ibl reads up to {}x{}, {} pixels)", kind, w, h,
                          kMaxImageDimension, kMaxImageDimension, kMaxImagePixels);
  return false;
}

// The smallest number of bytes a PNG or JPEG of its declared size can hold, so that a header
// claiming a large image over a few bytes of data is refused before the decoder allocates for it.
// PNG: deflate expands at most 1032 times, and the filtered rows take height x (1 + row bytes).
// JPEG: every 8x8 block takes at least a bit in some scan, and no real JPEG holds fewer than one
// byte per 4096 pixels (the densest, a flat gray progressive image, takes one per 512).
ImageProbe probeImage(std::span<const std::uint8_t> b) {
  ImageProbe r;
  static constexpr std::uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (b.size() >= 8 && std::memcmp(b.data(), kPng, 8) == 0) {
    if (b.size() < 33 || std::memcmp(b.data() + 12, "IHDR", 4) != 0) {
      r.problem = "a PNG without its IHDR chunk";
      return r;
    }
    const u64 width = readBe32(b.data() + 16), height = readBe32(b.data() + 20);
    const unsigned depth = b[24], colorType = b[25];
    const unsigned channels = colorType == 0   ? 1
                              : colorType == 2 ? 3
                              : colorType == 3 ? 1
                              : colorType == 4 ? 2
                              : colorType == 6 ? 4
                                               : 0;
    if (!channels || !(depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16)) {
      r.problem = "a PNG of an invalid color type or bit depth";
      return r;
    }
    if (!withinPixelLimits("PNG", width, height, r)) return r;
    u64 idat = 0;
    for (std::size_t at = 8; at + 8 <= b.size();) {
      const u64 length = readBe32(b.data() + at);
      if (std::memcmp(b.data() + at + 4, "IDAT", 4) == 0) idat += length;
      if (std::memcmp(b.data() + at + 4, "IEND", 4) == 0 || length > b.size() - at - 8) break;
      at += 12 + static_cast<std::size_t>(length);
    }
    const u64 rows = height * (1 + (width * depth * channels + 7) / 8);
    if (rows > 1032 * idat + 1024) {
      r.problem = fmt::format("a PNG whose {} bytes of image data cannot hold {}x{} pixels", idat,
                              width, height);
      return r;
    }
    r.width = static_cast<int>(width);
    r.height = static_cast<int>(height);
    return r;
  }
  if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) {
    int w = 0, h = 0, comp = 0;
    if (b.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
        !stbi_info_from_memory(b.data(), static_cast<int>(b.size()), &w, &h, &comp)) {
      r.problem = fmt::format("a JPEG whose header cannot be read ({})", stbi_failure_reason());
      return r;
    }
    if (!withinPixelLimits("JPEG", static_cast<u64>(w), static_cast<u64>(h), r)) return r;
    const u64 pixels = static_cast<u64>(w) * static_cast<u64>(h);
    if (pixels > 4096 * u64{b.size()}) {
      r.problem = fmt::format("a JPEG whose {} bytes cannot hold {}x{} pixels", b.size(), w, h);
      return r;
    }
    r.width = w;
    r.height = h;
    return r;
  }
  // WebP (EXT_texture_webp): its header through libwebp. No size bound holds here (a lossless
  // WebP of one color takes a few bytes at any size): the pixel limits and the textures' byte
  // limit bound the decoding.
  if (isWebp(b)) {
    int w = 0, h = 0;
    if (!WebPGetInfo(b.data(), b.size(), &w, &h)) {
      r.problem = "a WebP whose header cannot be read";
      return r;
    }
    if (!withinPixelLimits("WebP", static_cast<u64>(w), static_cast<u64>(h), r)) return r;
    r.width = w;
    r.height = h;
    return r;
  }
  r.problem = "not a PNG, JPEG or WebP image";
  return r;
}

// A glTF sampler's wrap mode (an OpenGL enum; absent: REPEAT).
Wrap wrapOf(int mode) {
  if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return Wrap::ClampToEdge;
  if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return Wrap::MirroredRepeat;
  return Wrap::Repeat;
}

}  // namespace

std::string GltfDocument::sourceName(int image) const {
  const ImageSource& s = images_[static_cast<std::size_t>(image)];
  if (s.bufferView >= 0) return fmt::format("buffer view {}", s.bufferView);
  if (parseDataUri(s.uri)) return "data URI";
  return s.uri;
}

std::string GltfDocument::imageLabel(int image) const {
  const ImageSource& s = images_[static_cast<std::size_t>(image)];
  if (s.bufferView < 0 && !parseDataUri(s.uri))
    return fmt::format("texture '{}' (image {})", s.uri, image);
  return fmt::format("texture image {} ({})", image, sourceName(image));
}

std::span<const std::uint8_t> GltfDocument::imageBytes(int image, ImageState& st) {
  const ImageSource& s = images_[static_cast<std::size_t>(image)];
  ownedBytes_.clear();
  if (s.bufferView >= 0) {
    const tinygltf::BufferView& bv = model_.bufferViews[static_cast<std::size_t>(s.bufferView)];
    st.key = fmt::format("view {} {} {}", bv.buffer, bv.byteOffset, bv.byteLength);
    return {model_.buffers[static_cast<std::size_t>(bv.buffer)].data.data() + bv.byteOffset,
            bv.byteLength};
  }
  if (const auto data = parseDataUri(s.uri)) {
    st.key = fmt::format("image {}", image);
    std::optional<std::vector<std::uint8_t>> bytes;
    if (data->base64) bytes = decodeBase64(data->payload);
    if (!bytes) {
      st.probe.problem = "a data URI that is not base64";
      return {};
    }
    ownedBytes_ = std::move(*bytes);
    return ownedBytes_;
  }
  const fs::path file = fs::path(path_).parent_path() / percentDecode(s.uri);
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    st.missing = true;
    return {};
  }
  const fs::path canonical = fs::weakly_canonical(file, ec);
  st.key = "file " + (ec ? file : canonical).string();
  try {
    ownedBytes_ = readFileBytes(file);
  } catch (const Error& e) {
    st.probe.problem = e.what();
    return {};
  }
  return ownedBytes_;
}

const GltfDocument::ImageState& GltfDocument::imageState(int image) {
  ImageState& st = imageStates_[image];
  if (!st.probed) {
    st.probed = true;
    const std::span<const std::uint8_t> bytes = imageBytes(image, st);
    if (!st.missing && st.probe.problem.empty()) st.probe = probeImage(bytes);
  }
  return st;
}

std::string GltfDocument::noSourceProblem(int texture) const {
  const tinygltf::Texture& g = model_.textures[static_cast<std::size_t>(texture)];
  std::string others;
  for (const auto& [name, value] : g.extensions) others += (others.empty() ? "" : ", ") + name;
  return others.empty() ? "no image" : "no PNG, JPEG or WebP image (only " + others + ")";
}

int GltfDocument::textureImage(int texture) const {
  const tinygltf::Texture& g = model_.textures[static_cast<std::size_t>(texture)];
  const auto webp = g.extensions.find("EXT_texture_webp");
  if (webp != g.extensions.end() && webp->second.IsObject())
    if (const auto source = extensionIndex(webp->second, "source", path_,
                                           fmt::format("texture {}: EXT_texture_webp", texture)))
      return *source;
  return g.source;
}

std::vector<Texture> GltfDocument::readTextures(bool decode) {
  std::map<int, std::shared_ptr<const std::vector<std::uint8_t>>> decoded;
  std::map<std::string, std::shared_ptr<const std::vector<std::uint8_t>>> byKey;
  u64 texelBytes = 0;
  DisjointRanges views;  // of the images decoded from buffer views
  std::set<int> warned;
  std::vector<Texture> textures;
  for (std::size_t t = 0; t < model_.textures.size(); ++t) {
    const tinygltf::Texture& g = model_.textures[t];
    Texture tex;
    tex.sampler = samplerOf(g.sampler);
    const bool used = usedTextures_.count(static_cast<int>(t)) > 0;
    const int k = textureImage(static_cast<int>(t));
    if (used && k < 0) {
      warn(fmt::format("texture {} has {}", t, noSourceProblem(static_cast<int>(t))),
           "rendering without it");
    } else if (used) {
      const ImageState& st = imageState(k);
      if (st.missing || !st.probe.problem.empty()) {
        if (warned.insert(k).second)
          warn(st.missing ? imageLabel(k) + " is missing"
                          : fmt::format("{} is {}", imageLabel(k), st.probe.problem),
               "rendering without it");
      } else if (decode) {
        auto& rgba = decoded[k];
        if (!rgba) {
          auto& shared = byKey[st.key];
          if (!shared) {
            ImageState scratch;
            const std::span<const std::uint8_t> bytes = imageBytes(k, scratch);
            if (const int v = images_[static_cast<std::size_t>(k)].bufferView; v >= 0) {
              const tinygltf::BufferView& bv = model_.bufferViews[static_cast<std::size_t>(v)];
              if (!views.add(bv.buffer, bv.byteOffset, bv.byteOffset + bv.byteLength))
                error(fmt::format("{}: the images' buffer views overlap", imageLabel(k)));
            }
            texelBytes += 4 * static_cast<u64>(st.probe.width) * st.probe.height;
            if (texelBytes > options_.maxTextureBytes)
              error(fmt::format("its textures decode to more than {} (the limit)",
                                formatBytes(options_.maxTextureBytes)));
            shared = decodeImage(k, bytes, st.probe);
          }
          rgba = shared;
        }
        if (rgba && !rgba->empty()) {
          tex.width = st.probe.width;
          tex.height = st.probe.height;
          tex.rgba = rgba;
        }
      }
    }
    textures.push_back(std::move(tex));
  }
  return textures;
}

std::shared_ptr<const std::vector<std::uint8_t>> GltfDocument::decodeImage(
    int image, std::span<const std::uint8_t> bytes, const ImageProbe& probe) {
  int w = 0, h = 0, comp = 0;
  if (isWebp(bytes)) {
    std::uint8_t* webp = WebPDecodeRGBA(bytes.data(), bytes.size(), &w, &h);
    if (!webp || w != probe.width || h != probe.height) {
      WebPFree(webp);
      warn(fmt::format("{} cannot be decoded (a damaged WebP)", imageLabel(image)),
           "rendering without it");
      return std::make_shared<const std::vector<std::uint8_t>>();
    }
    auto out = std::make_shared<std::vector<std::uint8_t>>(
        webp, webp + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
    WebPFree(webp);
    return out;
  }
  unsigned char* px =
      stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &comp, 4);
  if (!px || w != probe.width || h != probe.height) {
    const std::string reason = px ? "its size changed while decoding" : stbi_failure_reason();
    stbi_image_free(px);
    warn(fmt::format("{} cannot be decoded ({})", imageLabel(image), reason),
         "rendering without it");
    return std::make_shared<const std::vector<std::uint8_t>>();
  }
  auto out = std::make_shared<std::vector<std::uint8_t>>(
      px, px + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
  stbi_image_free(px);
  return out;
}

TextureSampler GltfDocument::samplerOf(int index) const {
  TextureSampler s;
  if (index < 0) return s;
  const tinygltf::Sampler& g = model_.samplers[static_cast<std::size_t>(index)];
  s.wrapS = wrapOf(g.wrapS);
  s.wrapT = wrapOf(g.wrapT);
  s.nearest = g.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
  s.mipmaps = g.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST &&
              g.minFilter != TINYGLTF_TEXTURE_FILTER_LINEAR;
  return s;
}

}  // namespace ibl::gltf
