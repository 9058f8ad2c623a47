#include "ibl/core/image.hpp"

#include <cmath>

namespace ibl {

Image::Image(int w, int h, glm::vec3 fill)
    : width(w), height(h), pixels(static_cast<std::size_t>(w) * h, fill) {}

InvalidPixelCounts& InvalidPixelCounts::operator+=(const InvalidPixelCounts& o) {
  nan += o.nan;
  infinite += o.infinite;
  negative += o.negative;
  return *this;
}

namespace {
template <bool kReplace, typename ImageRef>
InvalidPixelCounts scanInvalid(ImageRef& image) {
  InvalidPixelCounts counts;
  for (auto& p : image.pixels) {
    for (int c = 0; c < 3; ++c) {
      const float v = p[c];
      bool bad = true;
      if (std::isnan(v)) {
        ++counts.nan;
      } else if (std::isinf(v)) {
        ++counts.infinite;
      } else if (v < 0.0f) {
        ++counts.negative;
      } else {
        bad = false;
      }
      if constexpr (kReplace) {
        if (bad) p[c] = 0.0f;
      }
    }
  }
  return counts;
}
}  // namespace

InvalidPixelCounts countInvalidPixels(const Image& image) {
  return scanInvalid<false>(image);
}
InvalidPixelCounts sanitizePixels(Image& image) {
  return scanInvalid<true>(image);
}

Image cropImage(const Image& image, int x0, int y0, int w, int h) {
  Image out(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) out.at(x, y) = image.at(x0 + x, y0 + y);
  return out;
}

Image rotateImage180(const Image& image) {
  Image out(image.width, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      out.at(x, y) = image.at(image.width - 1 - x, image.height - 1 - y);
  return out;
}

}  // namespace ibl
