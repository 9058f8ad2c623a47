#pragma once
// API: internal (may change without notice; renderer internals behind render/renderer.hpp)
// Shadows of the analytic lights in the real-time paths (the CPU split sum and the viewer): each
// light's shadow-map layers planned from the scene and the camera (the sun's cascades fitted to
// the view and texel-snapped; a perspective map over a spot's cone; a cube around point, sphere,
// tube, disk and rect lights), their depths traced through the scene at the texel centers, and
// the exact alternative the maps are measured against (ray-traced visibility per light sample).
// The lookup and the filter are ibl/shared/shadows.h, which the viewer's shader includes too.
#include <cstddef>
#include <memory>
#include <string_view>
#include <vector>

#include "ibl/render/camera.hpp"
#include "ibl/render/light.hpp"
#include "ibl/render/scene.hpp"
#include "ibl/shared/shadows.h"

namespace ibl {

// How the real-time paths shadow the lights: not at all, through shadow maps, or by tracing
// rays to samples of each light (the CPU split sum only: the bound a map can reach).
enum class ShadowMode { None, Map, Ray };
std::string_view shadowModeName(ShadowMode mode);  // "none", "map", "ray"

struct ShadowSettings {
  int mapSize = 1024;   // texels per side of every layer (a power of two, 16 to 8192)
  int cascades = 4;     // the sun's cascades, 1 to 4
  int raySamples = 16;  // ShadowMode::Ray: rays per area light or sun and pixel sample
};

// Every light's shadow maps: one ShadowCaster per light (in the lights' order), the layers they
// refer to, the layers' depths (layer after layer, rows of mapSize texels) and, where the scene
// has surfaces that transmit, their filters in the same order (empty otherwise; see
// ibl/shared/shadows.h for what a texel stores).
struct ShadowMaps {
  int mapSize = 0;
  std::vector<shared::ShadowCaster> casters;
  std::vector<shared::ShadowLayer> layers;
  std::vector<float> depths;
  std::vector<glm::vec4> filters;
  // What ibl/shared/shadows.h reads on the CPU.
  shared::ShadowMapView view() const;
};

// The layers a light needs: the sun `cascades`, a spot of outer half-angle up to 60 degrees 1,
// every other light 6 (a cube).
int shadowLayerCount(const Light& light, const ShadowSettings& settings);
// The bytes of the depths of all `lights`' maps, and of their filters where `filtered` (for the
// memory check before the work).
std::size_t shadowMapBytes(const std::vector<Light>& lights, const ShadowSettings& settings,
                           bool filtered);

// Whether the scene's surfaces can shadow one another: not when it is one sphere alone. A convex
// object's only surface between one of its points and a light is its own, below that point's
// horizon, which the shading clips already (n.l, the area lights' horizon): its maps would cost
// their building and filtering and change nothing but their bias (the built-in `sphere` under a
// lights file spent 5.5 of 7.6 s on them). A sphere that transmits does: the light from behind
// it passes its far side on the way to its near side's transmission.
bool sceneCastsShadows(const Scene& scene);

// Plans every light's layers for a scene whose geometry lies within `bounds` (min, max corners):
// the cascades are fitted to `camera`'s view (null: one cascade over the whole scene), every
// other layer to the light. The depths are left empty.
ShadowMaps planShadowMaps(const std::vector<Light>& lights, std::pair<glm::vec3, glm::vec3> bounds,
                          const Camera* camera, const ShadowSettings& settings);

// Whether two layers are planned alike (the same light space and depth range): a layer planned
// as before keeps its depths.
bool sameShadowLayer(const shared::ShadowLayer& a, const shared::ShadowLayer& b);

class RayTracer;  // src/render/ray_tracer.hpp

// Builds the shadow maps of lights over a scene's geometry (the scene is traced through Embree
// once; it must outlive the builder). Thread-safe: build() may run while another thread renders.
class ShadowMapBuilder {
 public:
  explicit ShadowMapBuilder(const Scene& scene);
  ~ShadowMapBuilder();
  ShadowMapBuilder(const ShadowMapBuilder&) = delete;
  ShadowMapBuilder& operator=(const ShadowMapBuilder&) = delete;
  // planShadowMaps over the scene's bounds, then each texel's depth: the first surface that
  // transmits nothing along the texel center's ray (shared::shadowRayOrigin,
  // shadowRayDirection), 1 where there is none; where the scene transmits, its filter: the
  // product of shared::shadowMapCrossing over the surfaces in front of it, and the first one's
  // depth (1: none). A layer planned exactly as one of `previous` (same size) takes its depths
  // and filters from there.
  ShadowMaps build(const std::vector<Light>& lights, const Camera* camera,
                   const ShadowSettings& settings, const ShadowMaps* previous = nullptr) const;

 private:
  const Scene& scene_;
  std::unique_ptr<RayTracer> owned_;
};

// The same over an existing tracer of `scene` (the renderer's).
ShadowMaps buildShadowMaps(const Scene& scene, const RayTracer& tracer,
                           std::pair<glm::vec3, glm::vec3> bounds, const std::vector<Light>& lights,
                           const Camera* camera, const ShadowSettings& settings,
                           const ShadowMaps* previous = nullptr);

}  // namespace ibl
