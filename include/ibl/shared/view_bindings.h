// API: internal (may change without notice; layouts shared with the shaders)
// The viewer's descriptor bindings, by name: set 0, the frame's (shaders/view/frame.glsl, written
// by src/gpu/frame_set.cpp and the parts that own each binding), and set 1, a material's
// textures (shaders/view/material.glsl, written by src/gpu/scene_upload.cpp). Each number is
// written once, here: C++ reads it as FrameBinding::Name and MaterialBinding::Name (scoped
// enumerations, with Count after the last), GLSL as the constants kFrameName and kMaterialName
// (layout(binding = kFrameSpecularMap)). C++ and GLSL (see lang.h).
#ifndef IBL_SHARED_VIEW_BINDINGS_H
#define IBL_SHARED_VIEW_BINDINGS_H
#include "ibl/shared/lang.h"

IBL_BEGIN

// clang-format off
// Set 0: one enumerator (C++) or constant (GLSL) per binding.
#ifdef __cplusplus
#define IBL_FRAME_BINDING(name, number) name = number,
enum class FrameBinding : uint {
#else
#define IBL_FRAME_BINDING(name, number) const int kFrame##name = number;
#endif
IBL_FRAME_BINDING(Uniforms, 0)          // the Frame block (FrameUniforms, std140)
IBL_FRAME_BINDING(SpecularMap, 1)
IBL_FRAME_BINDING(IrradianceMap, 2)
IBL_FRAME_BINDING(DfgLut, 3)
IBL_FRAME_BINDING(SourceMap, 4)
IBL_FRAME_BINDING(Lights, 5)            // the lights' records
IBL_FRAME_BINDING(LtcTable, 6)
IBL_FRAME_BINDING(IesTable, 7)
IBL_FRAME_BINDING(Probes, 8)            // the local probes' placements
IBL_FRAME_BINDING(ProbeSpecularMaps, 9)
IBL_FRAME_BINDING(ProbeIrradianceMaps, 10)
IBL_FRAME_BINDING(SheenMap, 11)
IBL_FRAME_BINDING(SheenDfgLut, 12)
IBL_FRAME_BINDING(CharlieTable, 13)     // the sheen's exact Lambda (charlie_table.h)
IBL_FRAME_BINDING(ShadowRecords, 14)    // read by the shadow maps' vertex shader too
IBL_FRAME_BINDING(ShadowDepths, 15)
IBL_FRAME_BINDING(LightClusters, 16)
IBL_FRAME_BINDING(VolumeIrradiance, 17) // the irradiance volume's atlases
IBL_FRAME_BINDING(VolumeDistance, 18)
IBL_FRAME_BINDING(VolumeProbes, 19)     // its probes' relocation records
IBL_FRAME_BINDING(ViewPositions, 20)    // the screen-space passes' from here on
IBL_FRAME_BINDING(ViewNormals, 21)
IBL_FRAME_BINDING(ScreenOcclusion, 22)
IBL_FRAME_BINDING(ScreenReflection, 23)
IBL_FRAME_BINDING(LitFrame, 24)
IBL_FRAME_BINDING(TracedReflection, 25)
IBL_FRAME_BINDING(TransmissionFrame, 26) // the opaque frame behind transmissive surfaces
#ifdef __cplusplus
Count
};
#endif
#undef IBL_FRAME_BINDING

// Set 1: a material's texture slots; bit b of MaterialFactors::textureMask (src/gpu/
// scene_upload.hpp) is slot b's.
#ifdef __cplusplus
#define IBL_MATERIAL_BINDING(name, number) name = number,
enum class MaterialBinding : uint {
#else
#define IBL_MATERIAL_BINDING(name, number) const int kMaterial##name = number;
#endif
IBL_MATERIAL_BINDING(BaseColor, 0)      // an sRGB format
IBL_MATERIAL_BINDING(MetallicRoughness, 1)
IBL_MATERIAL_BINDING(Normal, 2)
IBL_MATERIAL_BINDING(Occlusion, 3)
IBL_MATERIAL_BINDING(Emissive, 4)       // an sRGB format
IBL_MATERIAL_BINDING(SheenColor, 5)     // an sRGB format
IBL_MATERIAL_BINDING(SheenRoughness, 6)
IBL_MATERIAL_BINDING(Specular, 7)       // KHR_materials_specular: its A
IBL_MATERIAL_BINDING(SpecularColor, 8)  // an sRGB format
IBL_MATERIAL_BINDING(Clearcoat, 9)      // KHR_materials_clearcoat: its R
IBL_MATERIAL_BINDING(ClearcoatRoughness, 10)  // its G
IBL_MATERIAL_BINDING(ClearcoatNormal, 11)
IBL_MATERIAL_BINDING(Iridescence, 12)  // KHR_materials_iridescence: its R
IBL_MATERIAL_BINDING(IridescenceThickness, 13)  // its G
IBL_MATERIAL_BINDING(Anisotropy, 14)  // KHR_materials_anisotropy: RG direction, B strength
IBL_MATERIAL_BINDING(Transmission, 15)  // KHR_materials_transmission: its R
IBL_MATERIAL_BINDING(Thickness, 16)     // KHR_materials_volume: its G
#ifdef __cplusplus
Count
};
#endif
#undef IBL_MATERIAL_BINDING
// After the textures: the material's factors and UV transforms, a storage buffer
// (MaterialFactors in src/gpu/scene_upload.hpp).
const int kMaterialFactors = 17;
// clang-format on

IBL_END

#endif
