#pragma once
// A linear RGB float image: the one in-memory pixel type of ibl.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

namespace ibl {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;  // row-major, row 0 first

  Image() = default;
  Image(int w, int h, glm::vec3 fill = glm::vec3(0.0f));

  glm::vec3& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const glm::vec3& at(int x, int y) const {
    return pixels[static_cast<std::size_t>(y) * width + x];
  }
  bool empty() const { return pixels.empty(); }
};

// Counts of pixel components that are not finite, non-negative radiance.
struct InvalidPixelCounts {
  std::size_t nan = 0;
  std::size_t infinite = 0;
  std::size_t negative = 0;
  std::size_t total() const { return nan + infinite + negative; }
  InvalidPixelCounts& operator+=(const InvalidPixelCounts& o);
};

// Counts NaN, infinite and negative components without changing the image.
InvalidPixelCounts countInvalidPixels(const Image& image);

// Replaces NaN, infinite and negative components by 0 and returns how many there were.
InvalidPixelCounts sanitizePixels(Image& image);

// Copies the w x h block whose top-left pixel is (x0, y0).
Image cropImage(const Image& image, int x0, int y0, int w, int h);

// Rotates an image by 180 degrees (the -Z face of a vertical cross is stored so).
Image rotateImage180(const Image& image);

}  // namespace ibl
