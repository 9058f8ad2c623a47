// OpenEXR through the OpenEXR library: every compression it implements (DWAA/DWAB included),
// half / float / uint channels, scanline and tiled files, RGB(A), Y and luminance-chroma.
#include <algorithm>
#include <cstring>
#include <mutex>
#include <optional>
#include <thread>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfRgbaFile.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>
#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/core/version.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/pixel_formats.hpp"
#include "ibl/math/color.hpp"

namespace ibl {

namespace {

class MemoryInput : public Imf::IStream {
 public:
  MemoryInput(std::span<const std::uint8_t> bytes, const std::string& name)
      : Imf::IStream(name.c_str()), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || pos_ + static_cast<std::uint64_t>(n) > bytes_.size())
      throw std::runtime_error("unexpected end of file");
    std::memcpy(c, bytes_.data() + pos_, static_cast<std::size_t>(n));
    pos_ += static_cast<std::uint64_t>(n);
    return pos_ < bytes_.size();
  }
  std::uint64_t tellg() override { return pos_; }
  void seekg(std::uint64_t pos) override {
    if (pos > bytes_.size()) throw std::runtime_error("seek past the end of file");
    pos_ = pos;
  }
  void clear() override {}

 private:
  std::span<const std::uint8_t> bytes_;
  std::uint64_t pos_ = 0;
};

class MemoryOutput : public Imf::OStream {
 public:
  MemoryOutput() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (pos_ + n > bytes.size()) bytes.resize(pos_ + n);
    std::memcpy(bytes.data() + pos_, c, static_cast<std::size_t>(n));
    pos_ += static_cast<std::uint64_t>(n);
  }
  std::uint64_t tellp() override { return pos_; }
  void seekp(std::uint64_t pos) override { pos_ = pos; }
  std::vector<std::uint8_t> bytes;

 private:
  std::uint64_t pos_ = 0;
};

void useAllCores() {
#if defined(__SANITIZE_THREAD__)
  // OpenEXR's thread pool is not built with ThreadSanitizer, which cannot see its
  // synchronization: under it, OpenEXR works on the calling thread.
  return;
#endif
  static std::once_flag once;
  std::call_once(once, [] {
    Imf::setGlobalThreadCount(static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  });
}

std::string_view compressionName(Imf::Compression c) {
  switch (c) {
    case Imf::NO_COMPRESSION:
      return "uncompressed";
    case Imf::RLE_COMPRESSION:
      return "RLE";
    case Imf::ZIPS_COMPRESSION:
      return "ZIPS";
    case Imf::ZIP_COMPRESSION:
      return "ZIP";
    case Imf::PIZ_COMPRESSION:
      return "PIZ";
    case Imf::PXR24_COMPRESSION:
      return "PXR24";
    case Imf::B44_COMPRESSION:
      return "B44";
    case Imf::B44A_COMPRESSION:
      return "B44A";
    case Imf::DWAA_COMPRESSION:
      return "DWAA";
    case Imf::DWAB_COMPRESSION:
      return "DWAB";
    default:
      return "unknown";
  }
}

std::string_view pixelTypeName(Imf::PixelType t) {
  switch (t) {
    case Imf::HALF:
      return "half";
    case Imf::FLOAT:
      return "float";
    case Imf::UINT:
      return "uint";
    default:
      return "unknown";
  }
}

std::string firstLine(const char* what) {
  std::string s(what);
  const auto nl = s.find('\n');
  return nl == std::string::npos ? s : s.substr(0, nl);
}

}  // namespace

Image decodeExr(std::span<const std::uint8_t> bytes, std::string_view name, DecodedFile* info,
                const DecodeOptions& options) {
  useAllCores();
  const std::string nameStr(name);
  try {
    MemoryInput stream(bytes, nameStr);
    Imf::InputFile file(stream);
    const Imf::Header& header = file.header();
    const Imath::Box2i dw = header.dataWindow();
    const std::int64_t w = static_cast<std::int64_t>(dw.max.x) - dw.min.x + 1;
    const std::int64_t h = static_cast<std::int64_t>(dw.max.y) - dw.min.y + 1;
    if (w <= 0 || h <= 0) fail(name, "empty or inverted data window");
    checkImageSize(name, static_cast<std::uint64_t>(w), static_cast<std::uint64_t>(h));
    const Imf::ChannelList& channels = header.channels();
    int channelCount = 0;
    const Imf::Channel* firstChannel = nullptr;
    for (auto it = channels.begin(); it != channels.end(); ++it) {
      ++channelCount;
      if (!firstChannel) firstChannel = &it.channel();
    }
    if (channelCount == 0) fail(name, "no channels");
    // Layers that hold a color: "L" when L.R, L.G and L.B exist ("" for plain R, G, B).
    const auto has = [&](const std::string& c) { return channels.findChannel(c) != nullptr; };
    const auto channelOf = [](const std::string& layer, const char* c) {
      return layer.empty() ? std::string(c) : layer + "." + c;
    };
    std::vector<std::string> rgbLayers;
    for (auto it = channels.begin(); it != channels.end(); ++it) {
      const std::string n = it.name();
      if (n.size() < 1 || n.back() != 'R' || (n.size() > 1 && n[n.size() - 2] != '.')) continue;
      const std::string layer = n.size() > 1 ? n.substr(0, n.size() - 2) : std::string();
      if (has(channelOf(layer, "G")) && has(channelOf(layer, "B"))) rgbLayers.push_back(layer);
    }
    const bool hasY = has("Y");
    const bool hasChroma = has("RY") || has("BY");
    const bool hasXyz = has("X") && hasY && has("Z");
    if (info) {
      info->channels = channelCount;
      info->layers = rgbLayers;
      info->detail = fmt::format("{}, {}{}", pixelTypeName(firstChannel->type),
                                 compressionName(header.compression()),
                                 header.hasTileDescription() ? ", tiled" : "");
    }
    const auto layerList = [&] {
      std::string list;
      for (const auto& l : rgbLayers)
        list += (list.empty() ? "" : ", ") + (l.empty() ? "(plain RGB)" : l);
      return list.empty() ? std::string("none") : list;
    };
    // The layer to read: the one asked for, the plain channels, or the only color layer.
    std::optional<std::string> layer;
    if (!options.layer.empty()) {
      if (std::find(rgbLayers.begin(), rgbLayers.end(), options.layer) == rgbLayers.end())
        fail(name, fmt::format("has no layer '{}' with R, G and B channels; its color layers: {}",
                               options.layer, layerList()));
      layer = options.layer;
    } else if (std::find(rgbLayers.begin(), rgbLayers.end(), std::string()) != rgbLayers.end()) {
      layer = std::string();
    } else if (rgbLayers.size() == 1 && !hasY) {
      layer = rgbLayers[0];
    } else if (rgbLayers.size() > 1) {
      fail(name, fmt::format("has {} color layers and no plain RGB: choose one with --layer "
                             "({})",
                             rgbLayers.size(), layerList()));
    }
    if (info && layer && !layer->empty()) info->detail += fmt::format(", layer {}", *layer);

    Image img(static_cast<int>(w), static_cast<int>(h));
    if (!layer && hasY && hasChroma) {
      // Luminance-chroma images: let the RGBA interface reconstruct RGB.
      MemoryInput rgbaStream(bytes, nameStr);
      Imf::RgbaInputFile rgbaFile(rgbaStream);
      std::vector<Imf::Rgba> px(static_cast<std::size_t>(w * h));
      rgbaFile.setFrameBuffer(px.data() - dw.min.x - dw.min.y * w, 1, static_cast<std::size_t>(w));
      rgbaFile.readPixels(dw.min.y, dw.max.y);
      for (std::size_t i = 0; i < px.size(); ++i) img.pixels[i] = {px[i].r, px[i].g, px[i].b};
      return img;
    }
    if (!layer && !hasY) {
      std::string names;
      for (auto it = channels.begin(); it != channels.end() && names.size() < 200; ++it)
        names += (names.empty() ? "" : ", ") + std::string(it.name());
      fail(name,
           fmt::format("has no color channels (R, G, B; Y; X, Y, Z) to read, only {}", names));
    }
    Imf::FrameBuffer fb;
    char* base = reinterpret_cast<char*>(img.pixels.data());
    const std::size_t xs = sizeof(glm::vec3), ys = xs * static_cast<std::size_t>(w);
    const char* const names[3] = {hasXyz && !layer ? "X" : "R", hasXyz && !layer ? "Y" : "G",
                                  hasXyz && !layer ? "Z" : "B"};
    if (layer || hasXyz) {
      for (int c = 0; c < 3; ++c)
        fb.insert(layer ? channelOf(*layer, names[c]) : std::string(names[c]),
                  Imf::Slice::Make(Imf::FLOAT, base + 4 * c, dw, xs, ys));
    } else {
      fb.insert("Y", Imf::Slice::Make(Imf::FLOAT, base, dw, xs, ys));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    if (!layer && hasXyz) {
      for (auto& p : img.pixels) p = xyzToLinearRec709(p);
    } else if (!layer) {
      for (auto& p : img.pixels) p.y = p.z = p.x;  // Y: gray
    }
    return img;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail(name, fmt::format("corrupt or unsupported OpenEXR file: {}", firstLine(e.what())));
  }
}

std::vector<std::uint8_t> encodeExr(const Image& img, ExrPixelType type,
                                    const std::vector<float>* alpha) {
  useAllCores();
  Imf::Header header(img.width, img.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  const Imf::PixelType pt = type == ExrPixelType::Half ? Imf::HALF : Imf::FLOAT;
  for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(pt));
  if (alpha) header.channels().insert("A", Imf::Channel(pt));
  std::vector<Imath::half> alphaHalves;
  header.insert("writer", Imf::StringAttribute(fmt::format("ibl {}", kVersion)));
  MemoryOutput out;
  {
    Imf::OutputFile file(out, header);
    Imf::FrameBuffer fb;
    // No infinity or NaN in any file: values are clamped to the type's range, NaN is 0.
    std::vector<Imath::half> halves;
    std::vector<glm::vec3> floats;
    if (type == ExrPixelType::Half) {
      halves.resize(img.pixels.size() * 3);
      for (std::size_t i = 0; i < img.pixels.size(); ++i) {
        const glm::vec3 v = representable(PixelFormat::Rgba16f, img.pixels[i]);
        for (int c = 0; c < 3; ++c) halves[3 * i + c] = Imath::half(v[c]);
      }
      char* base = reinterpret_cast<char*>(halves.data());
      const std::size_t xs = 3 * sizeof(Imath::half), ys = xs * img.width;
      for (int c = 0; c < 3; ++c)
        fb.insert(std::string(1, "RGB"[c]), Imf::Slice(Imf::HALF, base + 2 * c, xs, ys));
    } else {
      floats.resize(img.pixels.size());
      for (std::size_t i = 0; i < img.pixels.size(); ++i)
        floats[i] = representable(PixelFormat::Rgba32f, img.pixels[i]);
      char* base = reinterpret_cast<char*>(floats.data());
      const std::size_t xs = sizeof(glm::vec3), ys = xs * img.width;
      for (int c = 0; c < 3; ++c)
        fb.insert(std::string(1, "RGB"[c]), Imf::Slice(Imf::FLOAT, base + 4 * c, xs, ys));
    }
    if (alpha) {
      if (type == ExrPixelType::Half) {
        alphaHalves.assign(alpha->begin(), alpha->end());
        fb.insert("A", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(alphaHalves.data()),
                                  sizeof(Imath::half), sizeof(Imath::half) * img.width));
      } else {
        fb.insert("A",
                  Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(alpha->data())),
                             sizeof(float), sizeof(float) * img.width));
      }
    }
    file.setFrameBuffer(fb);
    file.writePixels(img.height);
  }
  return std::move(out.bytes);
}

}  // namespace ibl
