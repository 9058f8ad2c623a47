// KHR_materials_iridescence in both render modes: a mirror in a white furnace reflects the thin
// film's Fresnel at its view (shared::thinFilmFresnel, checked against the Airy sum over the
// spectrum in tests/shared/test_iridescence.cpp), on a dielectric and on a metal, at four views;
// and glTF files carry every part of the extension (factors, the strength's and the thickness's
// textures) into the renderer and `ibl info`, forbidden values refused.
#include <cmath>
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../../src/render/ray_tracer.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/shared/iridescence.h"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/material_quads.hpp"
#include "support/sphere_renders.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

const Baked& filmFurnace() {
  static const Baked b = bakeOf([](glm::vec3) { return glm::vec3(1.0f); }, 32);
  return b;
}

// The unit sphere's pixel at n.v = `cosine`, seen head-on through a one-pixel orthographic view.
glm::vec3 sphereAt(const Scene& s, double cosine, RenderOptions o) {
  Camera c = sphereCamera(1);
  c.orthoWidth = 0.002f;
  const float x = static_cast<float>(std::sqrt(1.0 - cosine * cosine));
  c.from = glm::vec3(x, 0.0f, 5.0f);
  c.at = glm::vec3(x, 0.0f, 0.0f);
  const Baked& b = filmFurnace();
  return renderScene(s, c, b.result, b.options, o).color.at(0, 0);
}

}  // namespace

// A mirror (roughness 0) under a film of index 1.35 and 380 nm, in a white furnace: each view
// shows the film's Fresnel at its n.v (a mirror's microfacet lies at v.h = n.v), in the split
// sum (whose DFG has A + B = 1 at roughness 0) and in the reference, on a dielectric (specular
// weight 0.8 of F0 0.04: the film sits on what the layer reflects, and nothing is diffuse) and
// on a colored metal, at strength 1 and 0.5 (the Schlick term mixed in). Taking the film's
// Fresnel at n.l, or the mix without the strength, fails this.
TEST(IridescenceRender, MirrorReflectsTheFilmsFresnel) {
  struct Base {
    glm::vec3 color;
    float metallic, specular;
  };
  const Base bases[] = {{glm::vec3(0.0f), 0.0f, 0.8f}, {{0.95f, 0.64f, 0.54f}, 1.0f, 1.0f}};
  for (const Base& base : bases)
    for (float strength : {1.0f, 0.5f}) {
      Material m;
      m.baseColor = base.color;
      m.metallic = base.metallic;
      m.roughness = 0.0f;
      m.specular = base.specular;
      m.iridescence = strength;
      m.iridescenceIor = 1.35f;
      m.iridescenceThicknessMaximum = 380.0f;
      const Scene scene = makeSphereScene(m);
      const glm::vec3 f0 = base.metallic > 0.0f ? base.color : glm::vec3(0.04f * base.specular);
      const float f90 = base.metallic > 0.0f ? 1.0f : base.specular;
      for (double cosine : {1.0, 0.8, 0.55, 0.3}) {
        const float c = static_cast<float>(cosine);
        const glm::vec3 schlickTerm = f0 + (glm::vec3(f90) - f0) * std::pow(1.0f - c, 5.0f);
        const glm::vec3 expected =
            glm::mix(schlickTerm, shared::thinFilmFresnel(1.0f, 1.35f, 380.0f, c, f0), strength);
        for (RenderMode mode : {RenderMode::SplitSum, RenderMode::Reference}) {
          RenderOptions o;
          o.mode = mode;
          o.spp = mode == RenderMode::Reference ? 16 : 1;
          o.multipleScattering = MultipleScattering::Off;
          const glm::vec3 seen = sphereAt(scene, cosine, o);
          for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(seen[k], expected[k], 0.01f * expected[k] + 2e-3f)
                << (mode == RenderMode::Reference ? "reference" : "split sum") << ", metallic "
                << base.metallic << ", strength " << strength << ", n.v " << cosine << ", channel "
                << k;
        }
      }
    }
}

// glTF carries every part of the extension: the strength is iridescenceFactor times its
// texture's R, the thickness mixes the minimum and maximum by its texture's G (the maximum
// without one), the film's index is read; `ibl info` reports them; forbidden values are refused
// with the file, the material and the value.
TEST(IridescenceRender, GltfCarriesTheFilmAndItsTextures) {
  TempDir dir;
  QuadMaterial q;
  q.metallicFactor = 0.0f;
  q.iridescenceFactor = 0.9f;
  q.iridescenceIor = 1.6f;
  q.iridescenceThicknessMinimum = 200.0f;
  q.iridescenceThicknessMaximum = 650.0f;
  writeMaterialQuad(dir / "plain.gltf", q);
  q.iridescenceCodes = {128, 64, 0};  // R 128 / 255 of the strength, G 64 / 255 of the way
  writeMaterialQuad(dir / "film.gltf", q);

  const SurfacePoint plain = quadSurface(loadGltf((dir / "plain.gltf").string()));
  EXPECT_NEAR(plain.iridescence, 0.9f, 1e-6f);
  EXPECT_NEAR(plain.iridescenceIor, 1.6f, 1e-6f);
  EXPECT_NEAR(plain.iridescenceThickness, 650.0f, 1e-3f) << "no texture: the maximum";
  const SurfacePoint p = quadSurface(loadGltf((dir / "film.gltf").string()));
  EXPECT_NEAR(p.iridescence, 0.9f * 128.0f / 255.0f, 1e-5f);
  EXPECT_NEAR(p.iridescenceThickness, 200.0f + 450.0f * 64.0f / 255.0f, 1e-2f);

  const CliRun info = runIbl("info " + quote(dir / "film.gltf") + " --json");
  ASSERT_EQ(info.status, 0) << info.output;
  const nlohmann::json j = nlohmann::json::parse(info.output);
  const nlohmann::json& m = j["materials"][0];
  EXPECT_NEAR(m["iridescence"].get<double>(), 0.9, 1e-6);
  EXPECT_NEAR(m["iridescence_ior"].get<double>(), 1.6, 1e-6);
  EXPECT_NEAR(m["iridescence_thickness"][0].get<double>(), 200.0, 1e-6);
  EXPECT_NEAR(m["iridescence_thickness"][1].get<double>(), 650.0, 1e-6);
  EXPECT_TRUE(m["unsupported_extensions"].empty()) << m.dump();

  expectExtensionRefused(
      dir / "film.gltf", "KHR_materials_iridescence",
      {{R"({"iridescenceFactor": 1.5})", "KHR_materials_iridescence iridescenceFactor: 1.5"},
       {R"({"iridescenceIor": 0.8})", "iridescenceIor: 0.8"},
       {R"({"iridescenceThicknessMinimum": -10})", "iridescenceThicknessMinimum: -10"},
       {R"({"iridescenceThicknessMaximum": "thick"})",
        "iridescenceThicknessMaximum: not a number"}});
}
