#include "ibl/render/environment_lighting.hpp"

#include <utility>

#include <nlohmann/json.hpp>

#include "ibl/env/photometry.hpp"
#include "ibl/io/json_file.hpp"

namespace ibl {

EnvironmentLighting readEnvironmentLighting(const std::filesystem::path& directory,
                                            const BakeOptions& options) {
  EnvironmentLighting out;
  out.options = options;
  out.bake = loadBake(directory, &out.options);
  // The sun the bake's environment brought (a sky's, or one extracted from the HDRI).
  const std::filesystem::path manifest = directory / "manifest.json";
  const nlohmann::json m = readJsonFile(manifest);
  if (m.contains("lights"))
    out.lights = parseLights(nlohmann::json({{"lights", m["lights"]}}).dump(), manifest.string(),
                             directory.string());
  return out;
}

EnvironmentLighting bakeEnvironmentLighting(const Environment& environment,
                                            std::vector<Light> lights, const BakeOptions& options) {
  EnvironmentLighting out;
  out.options = options;
  out.lights = std::move(lights);
  out.bake = bakeEnvironment(environment, out.options);
  return out;
}

EnvironmentLighting unlitEnvironmentLighting(const BakeOptions& options) {
  Environment black;
  black.equirect = Image(64, 32);
  EnvironmentLighting out;
  out.options = options;
  out.options.specular.size = 16;
  out.options.irradianceSize = 8;
  out.bake = bakeEnvironment(black, out.options);
  return out;
}

double horizontalIlluminance(const EnvironmentLighting& lighting) {
  // The source cube (level 0) with the suns give what the environment's own illuminance was.
  Environment source;
  source.layout = Layout::Cube;
  source.cube.levels.push_back(lighting.bake.source.levels.at(0));
  return horizontalIlluminance(source, lighting.lights);
}

void scaleEnvironmentLighting(EnvironmentLighting& lighting, double factor, std::string_view name) {
  scaleBake(lighting.bake, factor, name);
  for (Light& light : lighting.lights) light.intensity *= static_cast<float>(factor);
}

}  // namespace ibl
