#pragma once
// The scenes of the shadow study, shared by the tests (tests/render/test_shadows.cpp, the
// viewer's parity test) and the error table (bench/lights.cpp --shadows): blockers over a floor
// lit by one light of each type, a blocker in front of a wall lit by a rect light (the
// penumbra), a spot in a closed room; and the measured difference between the real-time shadows
// and the reference's ray-traced visibility.
#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "ibl/math/color.hpp"
#include "ibl/render/renderer.hpp"
#include "light_scenes.hpp"
#include "room.hpp"
#include "support/glass.hpp"

namespace ibl::test {

// An axis-aligned box of half extents h centered at c, faces outward.
inline void addBox(Scene& scene, glm::vec3 c, glm::vec3 h, int material) {
  const glm::vec3 lo = c - h, size = 2.0f * h;
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2, a = (axis + 1) % 3, b = (axis + 2) % 3;
    glm::vec3 corner = lo, u(0.0f), v(0.0f);
    if (face % 2 == 1) corner[axis] += size[axis];
    u[a] = size[a];
    v[b] = size[b];
    // addQuad turns the normal toward `inside`: a point beyond the face, away from the box.
    glm::vec3 outside = corner + 0.5f * (u + v);
    outside[axis] += face % 2 == 1 ? 1.0f : -1.0f;
    addQuad(scene, corner, u, v, material, outside);
  }
}

// The light of each type over the blockers: the light study's, higher (2.2 to 2.5 m) so that
// the blockers' shadows fall on the floor beside them.
inline Light shadowStudyLight(LightType type) {
  Light l = studyLight(type);
  if (type != LightType::Sun) l.position += glm::vec3(0.0f, 1.0f, 0.0f);
  if (type == LightType::Sun) l.intensity = 1000.0f;  // lx
  return l;
}

// A 6 x 6 m floor (y = 0), a sphere of radius 0.4 at (-0.6, 0.5, 0) and a box of 0.6 m at
// (0.7, 0.3, -0.4), grey and rough, lit by `light`.
inline Scene blockersOverFloor(const Light& light) {
  Material m;
  m.baseColor = glm::vec3(0.6f);
  m.roughness = 0.6f;
  Scene s;
  s.materials = {m};
  s.meshes.push_back(planeMesh(3.0f));
  s.spheres.push_back({glm::vec3(-0.6f, 0.5f, 0.0f), 0.4f, 0});
  addBox(s, glm::vec3(0.7f, 0.3f, -0.4f), glm::vec3(0.3f), 0);
  s.lights = {light};
  return s;
}

// The floor from above (orthographic, 4.4 m wide): the blockers and their shadows.
inline Camera floorCamera(int n) {
  Camera c = topDownCamera(glm::vec3(0.0f), 4.4f, n);
  c.from = glm::vec3(0.0f, 10.0f, 2.0f);  // slightly tilted: the box's sides show
  return c;
}

// A wall (the plane z = 0, facing +Z), a 0.6 x 0.6 m blocker 0.5 m in front of it, and a
// 1.2 x 0.6 m rect light 2 m from the wall, 1.2 m to the left, facing it: the blocker's shadow
// falls to its right, its umbra from x = 0.2 to 0.6 and its penumbra from 0.6 to 1.0 m.
inline Scene penumbraScene() {
  Material m;
  m.baseColor = glm::vec3(0.7f);
  m.roughness = 0.8f;
  Scene s;
  s.materials = {m};
  addQuad(s, glm::vec3(-3.0f, -3.0f, 0.0f), glm::vec3(6, 0, 0), glm::vec3(0, 6, 0), 0,
          glm::vec3(0, 0, 1));
  addQuad(s, glm::vec3(-0.3f, -0.3f, 0.5f), glm::vec3(0.6f, 0, 0), glm::vec3(0, 0.6f, 0), 0,
          glm::vec3(0, 0, 2));
  Light l;
  l.type = LightType::Rect;
  l.name = "penumbra light";
  l.position = {-1.2f, 0.0f, 2.0f};
  l.direction = {0.0f, 0.0f, -1.0f};
  l.up = {0.0f, 1.0f, 0.0f};
  l.width = 1.2f;
  l.height = 0.6f;
  l.intensity = 1000.0f;
  checkLight(l);
  s.lights = {l};
  return s;
}

// The wall straight on, 3 m wide.
inline Camera wallCamera(int n) {
  Camera c;
  c.perspective = false;
  c.orthoWidth = 3.0f;
  c.from = {0.0f, 0.0f, 10.0f};
  c.at = {0.0f, 0.0f, 0.0f};
  c.width = c.height = n;
  return c;
}

// A closed 4 x 3 x 4 m room, a table-like box in it, lit by a spot under the ceiling.
inline Scene spotInRoom() {
  Material wall;
  wall.baseColor = glm::vec3(0.7f);
  wall.roughness = 0.9f;
  RoomDescription room;
  room.tiles = 1;
  for (auto& w : room.walls) w = {wall, wall};
  Scene s = makeRoom(room);
  addBox(s, glm::vec3(0.3f, 0.5f, 0.2f), glm::vec3(0.5f, 0.5f, 0.3f), 0);
  Light l;
  l.type = LightType::Spot;
  l.name = "room spot";
  l.position = {-0.5f, 2.8f, -0.3f};
  l.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  l.innerAngle = 0.5f;
  l.outerAngle = 0.8f;
  l.intensity = 500.0f;
  checkLight(l);
  s.lights = {l};
  return s;
}

// The room from a corner, perspective.
inline Camera roomCamera(int n) {
  Camera c;
  c.yfovDegrees = 75.0f;
  c.from = {1.8f, 2.6f, 1.8f};
  c.at = {-0.2f, 0.3f, -0.2f};
  c.width = c.height = n;
  return c;
}

// A 60 x 60 m floor with thin poles (6 cm square, 1.5 m tall) 3, 7 and 16 m in front of a
// camera 3 m up at (0, 3, 4) looking down the field, lit by a sun from the right: each pole's
// shadow is resolved only by a cascade fitted to its distance.
inline Scene polesOnAField() {
  Material m;
  m.baseColor = glm::vec3(0.5f);
  m.roughness = 0.7f;
  Scene s;
  s.materials = {m};
  s.meshes.push_back(planeMesh(30.0f));
  for (float z : {1.0f, -3.0f, -12.0f})
    addBox(s, glm::vec3(0.5f, 0.75f, z), glm::vec3(0.03f, 0.75f, 0.03f), 0);
  Light sun;
  sun.type = LightType::Sun;
  sun.name = "field sun";
  sun.direction = glm::normalize(glm::vec3(1.0f, 0.8f, -0.3f));
  sun.intensity = 1000.0f;
  checkLight(sun);
  s.lights = {sun};
  return s;
}
inline Camera fieldCamera(int width, int height) {
  Camera c;
  c.yfovDegrees = 50.0f;
  c.from = {0.0f, 3.0f, 4.0f};
  c.at = {0.0f, 0.0f, -6.0f};
  c.width = width;
  c.height = height;
  return c;
}

struct ShadowError {
  double compared = 0.0;          // pixels compared (lit without shadows)
  double stateMismatch = 0.0;     // share whose state (visibility above or below 1/2) differs
  double shadowMismatch = 0.0;    // the same, of the pixels either shadows
  double medianVisibility = 0.0;  // median |visibility - the reference's| where either is < 0.99
  double acne = 0.0;      // share of the pixels the reference lights fully (visibility > 0.999)
                          // that are less than 0.9 visible
  double relative = 0.0;  // sum |radiance - the reference's| / sum of the reference's
  double referenceShadowed = 0.0;  // share of the compared pixels the reference shadows
};

// Per pixel: the share of the light that reaches it, as a shadowed render over the same render
// without shadows (1 where the latter is black).
inline std::vector<double> visibilityOf(const RenderResult& shadowed, const RenderResult& open) {
  std::vector<double> v(shadowed.color.pixels.size(), 1.0);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double a = luminance(shadowed.color.pixels[i]), b = luminance(open.color.pixels[i]);
    if (b > 0.0) v[i] = std::clamp(a / b, 0.0, 1.0);
  }
  return v;
}

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// The lights' real-time shadows (options.realTimeShadows, split sum) against the reference's
// (--bounces 0 --shadows ray, `spp` samples): each as a render over its own render without shadows,
// compared over the pixels that the light reaches without shadows and that do not see it.
struct ShadowStudy {
  RenderResult reference, referenceOpen, fast, fastOpen;
};
inline ShadowStudy renderShadowStudy(const Scene& scene, const Camera& camera,
                                     const BlackBake& bake, RenderOptions options, int spp) {
  options.environmentLight = false;
  options.backgroundEnvironment = false;
  options.cameraSeesEmitters = false;
  ShadowStudy s;
  RenderOptions ref = options;
  ref.mode = RenderMode::Reference;
  ref.spp = spp;
  ref.shadows = true;
  s.reference = renderScene(scene, camera, bake.result, bake.options, ref);
  ref.shadows = false;
  s.referenceOpen = renderScene(scene, camera, bake.result, bake.options, ref);
  options.mode = RenderMode::SplitSum;
  s.fast = renderScene(scene, camera, bake.result, bake.options, options);
  options.realTimeShadows = ShadowMode::None;
  s.fastOpen = renderScene(scene, camera, bake.result, bake.options, options);
  return s;
}

inline ShadowError compareShadows(const ShadowStudy& s) {
  const std::vector<double> vRef = visibilityOf(s.reference, s.referenceOpen);
  const std::vector<double> vFast = visibilityOf(s.fast, s.fastOpen);
  double peak = 0.0;
  for (const glm::vec3& c : s.referenceOpen.color.pixels)
    peak = std::max(peak, double(luminance(c)));
  ShadowError e;
  std::vector<double> dv;
  double diff = 0.0, sum = 0.0, mismatched = 0.0, shadowed = 0.0, eitherShadowed = 0.0;
  double fullyLit = 0.0, acne = 0.0;
  for (std::size_t i = 0; i < vRef.size(); ++i) {
    if (s.referenceOpen.alpha[i] < 1.0f || s.fastOpen.alpha[i] < 1.0f) continue;
    if (luminance(s.referenceOpen.color.pixels[i]) < 1e-3 * peak) continue;
    if (luminance(s.fastOpen.color.pixels[i]) <= 0.0f) continue;
    e.compared += 1.0;
    if ((vRef[i] < 0.5) != (vFast[i] < 0.5)) mismatched += 1.0;
    if (vRef[i] < 0.5) shadowed += 1.0;
    if (vRef[i] < 0.5 || vFast[i] < 0.5) eitherShadowed += 1.0;
    if (vRef[i] > 0.999) {
      fullyLit += 1.0;
      if (vFast[i] < 0.9) acne += 1.0;
    }
    if (vRef[i] < 0.99 || vFast[i] < 0.99) dv.push_back(std::abs(vRef[i] - vFast[i]));
    diff += std::abs(double(luminance(s.fast.color.pixels[i])) -
                     luminance(s.reference.color.pixels[i]));
    sum += luminance(s.reference.color.pixels[i]);
  }
  if (e.compared > 0.0) {
    e.stateMismatch = mismatched / e.compared;
    e.referenceShadowed = shadowed / e.compared;
    e.shadowMismatch = eitherShadowed > 0.0 ? mismatched / eitherShadowed : 0.0;
    e.acne = fullyLit > 0.0 ? acne / fullyLit : 0.0;
    e.medianVisibility = median(dv);
    e.relative = sum > 0.0 ? diff / sum : 0.0;
  }
  return e;
}

// The width of the penumbra along the image row through the center: the distance (world units,
// `worldPerPixel` per pixel) over which the visibility rises from 0.1 to 0.9, right of the
// darkest pixel of the row's right half.
inline double penumbraWidth(const std::vector<double>& visibility, int width, int height,
                            double worldPerPixel) {
  const int row = height / 2;
  const double* v = visibility.data() + static_cast<std::size_t>(row) * width;
  int darkest = width / 2;
  for (int x = width / 2; x < width; ++x)
    if (v[x] < v[darkest]) darkest = x;
  int lo = -1, hi = -1;
  for (int x = darkest; x < width; ++x) {
    if (lo < 0 && v[x] >= 0.1) lo = x;
    if (hi < 0 && v[x] >= 0.9) hi = x;
  }
  if (lo < 0 || hi < 0) return 0.0;
  return (hi - lo) * worldPerPixel;
}

}  // namespace ibl::test
