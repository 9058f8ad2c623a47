// Images and textures (src/render/gltf/images.cpp): samplers and UV sets, textures in the
// render, missing and unreadable images as warnings, the texel limit.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <gtest/gtest.h>
#include <webp/encode.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "ibl/core/image.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/render/renderer.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/hostile_gltf.hpp"

using namespace ibl;
using namespace ibl::test;
using nlohmann::json;

namespace {
// An 8 x 8 orthographic view of the 2 x 2 quad, diffuse only (Lambert, no specular layer to take
// its share: glTF's fresnel_mix) under constant white light: each pixel's radiance is the base
// color there.
RenderResult renderLambertUnderWhiteLight(Scene s) {
  for (Material& m : s.materials) m.specular = 0.0f;
  BakeOptions bo;
  bo.specular.size = 16;
  bo.dfgSize = 16;
  bo.dfgSamples = 64;
  const BakeResult bake = bakeEnvironment(equirectEnvironment(Image(64, 32, glm::vec3(1.0f))), bo);
  RenderOptions o;
  o.spp = 1;
  o.only = ShadingTerms::Diffuse;
  o.diffuse = DiffuseModel::Lambert;
  return renderScene(s, frontOrthoCamera(2.0f, 8), bake, bo, o);
}
}  // namespace

TEST(Gltf, SamplersAndTheSecondUvSet) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf", true);
  const Scene s = loadGltf((dir / "quad.gltf").string());
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.uvs1.size(), 4u);
  const Material& mat = s.materials[m.material];
  EXPECT_EQ(mat.baseColorTexture.texCoord, 1);
  EXPECT_EQ(mat.normalTexture.texCoord, 0);
  const TextureSampler& sampler = s.textures[mat.baseColorTexture.index].sampler;
  EXPECT_EQ(sampler.wrapS, Wrap::ClampToEdge);
  EXPECT_EQ(sampler.wrapT, Wrap::MirroredRepeat);
  EXPECT_TRUE(sampler.nearest);
  EXPECT_FALSE(sampler.mipmaps);  // minFilter LINEAR: no mip maps
  EXPECT_EQ(s.textures[mat.normalTexture.index].sampler, TextureSampler{});  // glTF defaults
  // Rendered: the mirrored UV set puts blue left and red right.
  const RenderResult r = renderLambertUnderWhiteLight(s);
  EXPECT_LT(glm::distance(r.color.at(2, 4), glm::vec3(0, 0, 1)), 0.02f);
  EXPECT_LT(glm::distance(r.color.at(5, 4), glm::vec3(1, 0, 0)), 0.02f);
}

TEST(Gltf, TexturesShowInTheRender) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf");
  const Scene s = loadGltf((dir / "quad.gltf").string());
  const RenderResult r = renderLambertUnderWhiteLight(s);
  // Constant white light, Lambert: radiance = albedo (the texture), left red, right blue.
  // (Texture columns 1 and 2 are sampled away from the wrap-around blend at u = 0 and 1.)
  EXPECT_LT(glm::distance(r.color.at(2, 4), glm::vec3(1, 0, 0)), 0.02f);
  EXPECT_LT(glm::distance(r.color.at(5, 4), glm::vec3(0, 0, 1)), 0.02f);
  EXPECT_FLOAT_EQ(r.alpha[4 * 8 + 2], 1.0f);
}

// A texture file that is missing, or not an image: a warning naming it, the render goes on
// without it; strict makes it an error. Unreadable images are treated alike.
TEST(GltfHostile, MissingAndUnreadableTexturesAreWarnings) {
  TempDir dir;
  json j = baseGltf();
  j["images"][0] = {{"uri", "textures/wood%20grain.png"}};
  const std::string path = write(dir, "missing.gltf", j);
  std::vector<std::string> warnings;
  GltfLoadOptions options;
  options.warn = [&](const std::string& w) { warnings.push_back(w); };
  const Scene s = loadGltf(path, options);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], path +
                             ": texture 'textures/wood%20grain.png' (image 0) is missing; "
                             "rendering without it");
  EXPECT_EQ(s.materials[0].baseColorTexture.index, -1);
  ASSERT_EQ(s.meshes.size(), 1u);
  options.strict = true;
  EXPECT_EQ(errorOf([&] { loadGltf(path, options); }),
            path + ": texture 'textures/wood%20grain.png' (image 0) is missing");
  // Present (the URI's %20 decoded), the same file loads with its texture and no warning.
  std::filesystem::create_directories(dir / "textures");
  writeFileAtomic(dir / "textures" / "wood grain.png", encodePng(Image(2, 2, glm::vec3(1.0f))));
  warnings.clear();
  EXPECT_GE(loadGltf(path, options).materials[0].baseColorTexture.index, 0);
  EXPECT_TRUE(warnings.empty());

  // Not an image, a PNG header claiming 16000 x 16000 pixels over a few bytes (refused before
  // the decoder allocates 1 GB for it), a data URI that is not base64.
  std::vector<std::uint8_t> png = encodePng(Image(1, 1, glm::vec3(1.0f)));
  for (int i = 0; i < 2; ++i) {  // IHDR width and height, big endian: 0x3E80
    png[16 + 4 * i] = 0;
    png[17 + 4 * i] = 0;
    png[18 + 4 * i] = 0x3E;
    png[19 + 4 * i] = 0x80;
  }
  std::size_t idat = 0;  // the bytes of its IDAT chunks
  for (std::size_t at = 8; at + 8 <= png.size();) {
    const std::size_t length =
        (png[at] << 24) | (png[at + 1] << 16) | (png[at + 2] << 8) | png[at + 3];
    if (std::string(png.begin() + at + 4, png.begin() + at + 8) == "IDAT") idat += length;
    at += 12 + length;
  }
  const struct {
    json image;
    std::string warning;
  } cases[] = {
      {{{"uri", "data:image/png;base64," + base64({'G', 'I', 'F', '8', '9', 'a', 0, 0})}},
       "texture image 0 (data URI) is not a PNG, JPEG or WebP image"},
      {{{"uri", "data:image/png;base64," + base64(png)}},
       fmt::format("texture image 0 (data URI) is a PNG whose {} bytes of image data cannot "
                   "hold 16000x16000 pixels",
                   idat)},
      {{{"uri", "data:image/png;base64,!!!!"}},
       "texture image 0 (data URI) is a data URI that is not base64"},
  };
  options.strict = false;
  for (const auto& c : cases) {
    j["images"][0] = c.image;
    const std::string p = write(dir, "bad.gltf", j);
    warnings.clear();
    EXPECT_EQ(loadGltf(p, options).materials[0].baseColorTexture.index, -1) << c.warning;
    ASSERT_EQ(warnings.size(), 1u) << c.warning;
    EXPECT_EQ(warnings[0], p + ": " + c.warning + "; rendering without it");
  }
}

// The decoded texels count against their limit (each image once, however many textures use it),
// and the buffer views of images may not overlap (else a few bytes could be decoded many times).
TEST(GltfHostile, TexturesAreCountedAgainstTheirLimit) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf");  // a 4x4 and a 1x1 image: 68 bytes of RGBA
  const std::string path = (dir / "quad.gltf").string();
  GltfLoadOptions options;
  options.maxTextureBytes = 68;
  const Scene s = loadGltf(path, options);
  EXPECT_GE(s.materials[0].baseColorTexture.index, 0);
  EXPECT_GE(s.materials[0].normalTexture.index, 0);
  options.maxTextureBytes = 67;
  EXPECT_EQ(errorOf([&] { loadGltf(path, options); }),
            path + ": its textures decode to more than 67 bytes (the limit)");

  // A GLB whose two images are the same PNG, one of them with 4 more bytes after its end: views
  // that overlap.
  const std::vector<std::uint8_t> png = encodePng(Image(2, 2, glm::vec3(1.0f)));
  auto [j, bin] = splitGlb(asGlb(baseGltf()));
  const std::size_t at = bin.size();
  bin.insert(bin.end(), png.begin(), png.end());
  bin.insert(bin.end(), 4, 0);
  j["buffers"][0]["byteLength"] = bin.size();
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", png.size()}});
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", png.size() + 4}});
  j["images"] = {{{"bufferView", 5}, {"mimeType", "image/png"}},
                 {{"bufferView", 6}, {"mimeType", "image/png"}}};
  j["textures"] = {{{"source", 0}}, {{"source", 1}}};
  j["materials"][0]["emissiveTexture"] = {{"index", 1}};
  const std::string glb = (dir / "overlap.glb").string();
  writeFileAtomic(glb, glbOf(j, bin));
  EXPECT_EQ(errorOf([&] { loadGltf(glb); }),
            glb + ": texture image 1 (buffer view 6): the images' buffer views overlap");
  // The same view twice: one image, decoded once.
  j["images"][1]["bufferView"] = 5;
  writeFileAtomic(glb, glbOf(j, bin));
  const Scene twice = loadGltf(glb);
  EXPECT_EQ(twice.textures[0].rgba, twice.textures[1].rgba);
}

// EXT_texture_webp: the texture's WebP source is read (lossless here: every texel comes back) and
// its core source is only the fallback; a damaged WebP is a warning naming the image, and the
// material renders without it.
TEST(Gltf, WebpTexturesAreDecoded) {
  TempDir dir;
  const std::vector<std::uint8_t> texels = {255, 0,  0,   255, 0,   128, 0,  200,
                                            10,  20, 200, 100, 255, 255, 64, 1};
  std::uint8_t* encoded = nullptr;
  const std::size_t size = WebPEncodeLosslessRGBA(texels.data(), 2, 2, 8, &encoded);
  ASSERT_GT(size, 0u);
  const std::vector<std::uint8_t> webp(encoded, encoded + size);
  WebPFree(encoded);
  json j = baseGltf();
  j["images"].push_back({{"uri", "data:image/webp;base64," + base64(webp)}});
  j["textures"][0]["extensions"]["EXT_texture_webp"] = {{"source", 1}};
  j["extensionsUsed"].push_back("EXT_texture_webp");
  std::vector<std::string> warnings;
  GltfLoadOptions options;
  options.warn = [&](const std::string& w) { warnings.push_back(w); };
  const Scene s = loadGltf(write(dir, "webp.gltf", j), options);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_EQ(s.textures.size(), 1u);
  ASSERT_EQ(s.textures[0].width, 2);
  ASSERT_EQ(s.textures[0].height, 2);
  EXPECT_EQ(*s.textures[0].rgba, texels);
  // `ibl info` names the WebP as the texture's image.
  const CliRun info = runIbl("info " + quote(dir / "webp.gltf") + " --json");
  ASSERT_EQ(info.status, 0) << info.output;
  EXPECT_EQ(json::parse(info.output)["textures"][0]["image"], 1);
  // Truncated: the header reads, the data does not.
  std::vector<std::uint8_t> damaged(webp.begin(),
                                    webp.begin() + static_cast<long>(webp.size() - 6));
  j["images"][1]["uri"] = "data:image/webp;base64," + base64(damaged);
  warnings.clear();
  const Scene broken = loadGltf(write(dir, "damaged.gltf", j), options);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("texture image 1 (data URI)"), std::string::npos) << warnings[0];
  EXPECT_EQ(broken.materials[0].baseColorTexture.index, -1);
}
