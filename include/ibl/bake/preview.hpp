#pragma once
// API: internal (may change without notice; the bake's preview picture, behind bake/bake.hpp)
// The picture a user looks at first: spheres of roughness 0..1 (columns), dielectric and metal
// (rows), lit by the baked assets with the split-sum model, over the environment, tone-mapped.
#include "ibl/bake/bake.hpp"
#include "ibl/core/image.hpp"

namespace ibl {

// Linear HDR image of the material grid (`columns` roughness steps, 2 rows, `cell` pixels per
// sphere, orthographic, seen from +Z), shaded by shadeSplitSum (render.hpp) with its defaults.
// Dielectric: base color 0.8; metal: base color 0.95 (aluminium-like).
Image renderMaterialGrid(const BakeResult& bake, const BakeOptions& options, int columns = 6,
                         int cell = 96);

// ACES filmic tone curve (Narkowicz 2015 fit) after scaling by 2^exposure, then sRGB-ready
// (linear values in [0, 1]).
Image toneMapAces(const Image& image, float exposure);

// Exposure (in stops) that maps the average luminance of an image to middle gray (0.18).
float autoExposure(const Image& image);

}  // namespace ibl
