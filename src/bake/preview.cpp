#include "ibl/bake/preview.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "ibl/core/parallel.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/renderer.hpp"

namespace ibl {

Image renderMaterialGrid(const BakeResult& bake, const BakeOptions& options, int columns,
                         int cell) {
  const int rows = 2;
  Image img(columns * cell, rows * cell);
  const glm::vec3 view(0.0f, 0.0f, 1.0f);  // orthographic camera on +Z looking toward -Z
  const RenderOptions shading;
  parallelFor(0, img.height, [&](int py) {
    for (int px = 0; px < img.width; ++px) {
      const int col = px / cell, row = py / cell;
      const float radius = 0.42f * static_cast<float>(cell);
      const float dx =
          (static_cast<float>(px % cell) + 0.5f - 0.5f * static_cast<float>(cell)) / radius;
      const float dy =
          (0.5f * static_cast<float>(cell) - static_cast<float>(py % cell) - 0.5f) / radius;
      const float d2 = dx * dx + dy * dy;
      if (d2 >= 1.0f) {  // background: the environment behind the grid, blurred a little
        const glm::vec3 dir = glm::normalize(glm::vec3(
            (static_cast<float>(px) / static_cast<float>(img.width) - 0.5f) * 1.6f,
            (0.5f - static_cast<float>(py) / static_cast<float>(img.height)) * 0.6f, -1.0f));
        img.at(px, py) = sampleTrilinear(bake.specular, 1.0f, dir) * 0.5f;
        continue;
      }
      SurfacePoint p{};
      p.normal = glm::vec3(dx, dy, std::sqrt(1.0f - d2));
      p.roughness = columns > 1 ? static_cast<float>(col) / static_cast<float>(columns - 1) : 0.5f;
      p.metallic = row == 0 ? 1.0f : 0.0f;  // metals on top, as in `ibl render grid`
      p.baseColor = glm::vec3(row == 0 ? 0.95f : 0.8f);
      img.at(px, py) = shadeSplitSum(p, view, bake, options, shading);
    }
  });
  return img;
}

Image toneMapAces(const Image& image, float exposure) {
  const float scale = std::exp2(exposure);
  Image out(image.width, image.height);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const glm::vec3 x = image.pixels[i] * scale;
    out.pixels[i] =
        glm::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
  }
  return out;
}

float autoExposure(const Image& image) {
  double sum = 0.0;
  for (const auto& p : image.pixels) sum += luminance(p);
  const double mean = sum / static_cast<double>(std::max<std::size_t>(1, image.pixels.size()));
  return mean > 0.0 ? static_cast<float>(std::log2(0.18 / mean)) : 0.0f;
}

}  // namespace ibl
