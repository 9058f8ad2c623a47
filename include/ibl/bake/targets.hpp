#pragma once
// API: stable
// Engine targets: a bake written the way an engine's own tool writes it, so that the engine
// loads it unchanged (docs/targets.md gives each convention and where it comes from).
//   ibl                 our own set (KTX2 cube maps, DFG table, SH9, manifest conventions)
//   filament            what Filament's `cmgen --format=ktx --deploy=DIR` writes
//   gltf-sample-viewer  what glTF-IBL-Sampler writes for the Khronos glTF Sample Viewer
//   dds                 DDS cube maps with their mip chains (DirectX, Unity, Unreal)
//   babylon             a Babylon.js .env (its IBL tool's output, CreateEnvTextureAsync)
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include <glm/mat3x3.hpp>

#include "ibl/io/pixel_formats.hpp"
#include "ibl/math/sh.hpp"

namespace ibl {

enum class EngineTarget { Ibl, Filament, GltfSampleViewer, Dds, Babylon };
inline constexpr std::array<EngineTarget, 5> kEngineTargets = {
    EngineTarget::Ibl, EngineTarget::Filament, EngineTarget::GltfSampleViewer, EngineTarget::Dds,
    EngineTarget::Babylon};

std::string_view targetName(EngineTarget target);                      // "ibl", "filament", ...
std::optional<EngineTarget> parseEngineTarget(std::string_view name);  // none for other names

// The bake's choices that an engine target may fix for itself, because its engine reads one
// format or one chain: the cube maps' texel format (--format), the specular levels (--levels)
// and their roughness mapping (--mapping), the irradiance cube's size, the DFG table's size
// and samples, the EXR/HDR copies and their layout, the previews, the Fresnel-weighted pair,
// the sheen, the SH window.
enum class BakeSetting {
  Format,
  Levels,
  Mapping,
  IrradianceSize,
  DfgTable,
  FileCopies,
  Previews,
  FresnelWeighted,
  Sheen,
  ShWindow
};
// What `target` writes whatever the choice of `setting` ("its fixed R11F_G11F_B10F (cmgen's)"),
// or nothing when the target writes what was chosen. `format`: the chosen texel format (the glTF
// Sample Viewer takes the float ones only).
std::optional<std::string_view> fixedByTarget(EngineTarget target, BakeSetting setting,
                                              PixelFormat format);

// --- Filament (cmgen --deploy) ---

// The axes of cmgen's cube maps: the texel a Filament app samples with direction d holds our
// environment at m d. cmgen mirrors X (its default; --no-mirror turns it off) after reading
// the input, and reads an equirect panorama with u = 0.5 + atan2(x, z) / (2 pi) where we use
// atan2(z, x): for a panorama m d = (d.z, d.y, -d.x), a quarter turn about +Y; for a cube map
// (a cross, faces) m d = (-d.x, d.y, d.z), the mirror alone.
// panoramaSource: the bake's input was an equirect panorama (else a cube layout).
glm::mat3 filamentOrientation(bool panoramaSource);

// The levels of cmgen's prefiltered cube map of base size n: n down to 16^2 (cmgen's
// IBL_DEFAULT_MIN_LOD_SIZE), or down to 1^2 when n <= 16; size: texels per side.
int filamentLevelCount(int size);

// Filament's irradiance spherical harmonics (cmgen's "irradiance, pre-scaled base", the
// coefficients of sh.txt and of the KTX "sh" key): E(n) / pi = c0 + c1 y + c2 z + c3 x
// + c4 y x + c5 y z + c6 (3 z^2 - 1) + c7 z x + c8 (x^2 - y^2) (Filament's
// Irradiance_SphericalHarmonics), from our radiance coefficients in the same frame (the
// radiance's units).
Sh9 filamentIrradianceSh(const Sh9& radiance);
// Filament's basis polynomials, in that order (1, y, z, x, y x, ...): k 0 to 8, n unit.
float filamentShPolynomial(int k, glm::vec3 n);
// sh.txt as cmgen writes it: "(r, g, b); // L00, irradiance, pre-scaled base", one line each;
// c: filamentIrradianceSh's coefficients.
std::string filamentShText(const Sh9& c);

// --- Babylon.js (.env) ---

// The axes of a Babylon.js environment: the texel Babylon samples with direction d holds our
// environment at m d. Babylon's HDRCubeTexture reads a panorama with u = 0.5 + atan2(z, x) /
// (2 pi) as we do, but through its face table (PanoramaToCubeMapTools) whose +X face ("right")
// looks down +Z: m d = (d.z, d.y, d.x), the swap of X and Z (Babylon's world is left-handed). A
// cube map is used as it is: m = identity.
// panoramaSource: as for filamentOrientation.
glm::mat3 babylonOrientation(bool panoramaSource);

// Babylon's SphericalPolynomial (x, y, z, xx, yy, zz, yz, zx, xy; the .env manifest's
// "irradiance") of irradiance coefficients in Filament's pre-scaled form (filamentIrradianceSh,
// E(n) / pi = sum c_k p_k(n), in Babylon's axes), as Babylon's own tool derives it:
// SphericalPolynomial.FromHarmonics of the harmonics c_k / K_k, K_k its signed basis constants.
// Babylon's PBR shader turns it back (SphericalHarmonics.FromPolynomial, preScaleForRendering)
// into the c_k and evaluates E(n) / pi.
std::array<glm::vec3, 9> babylonSphericalPolynomial(const Sh9& prescaled);

}  // namespace ibl
