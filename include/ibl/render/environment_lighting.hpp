#pragma once
// API: stable
// The environment lighting of a render: a bake read back from its folder, or an environment
// baked for the render, with the lights the environment brings (a sky's sun, or the sun taken
// out of an HDRI). What `ibl render`, `ibl view` and `ibl probe` light a scene with (--bake,
// --env); renderScene takes its bake and options, the scene its lights.
#include <filesystem>
#include <string_view>
#include <vector>

#include "ibl/bake/bake.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/render/light.hpp"

namespace ibl {

struct EnvironmentLighting {
  BakeResult bake;
  // The bake's options: its specular size and roughness mapping, and the sheen lobe's visibility
  // of its sheen table, the one a split sum must render with (RenderOptions::sheenVisibility).
  BakeOptions options;
  // The environment's suns, in lux (a sky's, or one extracted from an HDRI): add them to the
  // scene's lights, since the bake holds the sky without its sun.
  std::vector<Light> lights;
};

// Reads the bake in `directory` (the files writeBakeOutputs writes: loadBake) and the lights its
// manifest records. options: the render's (BakeOptions::sheen for a scene with a sheen layer,
// hasSheen; the sheen visibility it asks for); the bake's specular size and roughness mapping
// replace options', and so does the visibility its sheen table was integrated with when it has
// one. Throws Error naming the directory, manifest.json or the file at fault (loadBake,
// parseLights).
EnvironmentLighting readEnvironmentLighting(const std::filesystem::path& directory,
                                            const BakeOptions& options = {});

// Bakes `environment` on the CPU (bakeEnvironment; any layout, in its own radiance units, which
// the bake keeps) with `options`, which a scene with a sheen layer (hasSheen) must ask the sheen
// chain of (BakeOptions::sheen). lights: the environment's suns (lux), kept with the bake.
// Throws as bakeEnvironment.
EnvironmentLighting bakeEnvironmentLighting(const Environment& environment,
                                            std::vector<Light> lights, const BakeOptions& options);

// No environment light (a scene lit by its lights alone): a black environment baked small (a
// specular cube of 16 texels, an irradiance cube of 8) with options' other choices, for the DFG
// (and sheen) tables the shading still reads. No lights.
EnvironmentLighting unlitEnvironmentLighting(const BakeOptions& options);

// The illuminance, in lux, of the lighting on an upward horizontal surface: its source cube's
// level 0 and its suns (horizontalIlluminance of env/photometry.hpp).
double horizontalIlluminance(const EnvironmentLighting& lighting);

// Multiplies the lighting's radiance (scaleBake: the source, specular, sheen and irradiance
// cubes and SH9, not the DFG tables) and its lights' intensities by `factor` (> 0 and finite),
// as if the environment and its suns had been scaled before baking: every stage of a bake is
// linear in the radiance. Throws Error("<name>: ...") as scaleBake.
void scaleEnvironmentLighting(EnvironmentLighting& lighting, double factor, std::string_view name);

}  // namespace ibl
