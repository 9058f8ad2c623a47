#pragma once
// API: stable
// A linear RGB float image: the one in-memory pixel type of ibl.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

namespace ibl {

// Pixel values are linear (never sRGB-encoded) in the units of their source: radiance of an HDR
// file in its own relative units, or 0..1 for data and decoded LDR files.
struct Image {
  int width = 0;                  // pixels
  int height = 0;                 // pixels
  std::vector<glm::vec3> pixels;  // row-major, row 0 first (the top), width x height entries

  Image() = default;
  // w, h: pixels, not checked against the limits (checkImageSize); every pixel set to `fill`.
  Image(int w, int h, glm::vec3 fill = glm::vec3(0.0f));

  // Pixel in column x, row y (0-based, row 0 at the top); not bounds-checked.
  glm::vec3& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const glm::vec3& at(int x, int y) const {
    return pixels[static_cast<std::size_t>(y) * width + x];
  }
  bool empty() const { return pixels.empty(); }  // no pixels (default-constructed)
};

// Counts of pixel components that are not finite, non-negative radiance.
// Counted per component (an RGB pixel counts up to 3).
struct InvalidPixelCounts {
  std::size_t nan = 0;
  std::size_t infinite = 0;  // +inf or -inf
  std::size_t negative = 0;  // finite and < 0 (-0 is not negative)
  std::size_t total() const { return nan + infinite + negative; }  // all three
  InvalidPixelCounts& operator+=(const InvalidPixelCounts& o);
};

// Counts NaN, infinite and negative components without changing the image.
InvalidPixelCounts countInvalidPixels(const Image& image);

// Replaces NaN, infinite and negative components by 0 and returns how many there were.
InvalidPixelCounts sanitizePixels(Image& image);

// Copies the w x h block (pixels) whose top-left pixel is (x0, y0); the block must lie inside
// the image (not checked).
Image cropImage(const Image& image, int x0, int y0, int w, int h);

// Rotates an image by 180 degrees (the -Z face of a vertical cross is stored so).
Image rotateImage180(const Image& image);

}  // namespace ibl
