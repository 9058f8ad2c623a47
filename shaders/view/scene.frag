#version 450
// Split-sum shading of the viewer's meshes: the material's textures and normal map as in
// surfaceAt (src/render/ray_tracer.cpp), through ibl/shared/material.h, then shadeSplitSum
// (view/shading.glsl), with the sheen layer of KHR_materials_sheen.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "ibl/shared/color.h"
#include "view/frame.glsl"
#include "view/shading.glsl"
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec4 worldTangent;
layout(location = 3) in vec2 texCoord0;
layout(location = 4) in vec2 texCoord1;
layout(location = 5) in vec4 vertexColor;
layout(location = 0) out vec4 outColor;
#include "view/material.glsl"
#include "view/surface.glsl"

void main() {
  ShadedSurface surface = fragmentSurface(frame.models.z);
  vec3 bentNormal = vec3(0.0);
  if (frame.ambientOcclusion.z > 0.0 && draw.scenePass != 3) {
    // Screen-space ambient occlusion (view/gtao.frag) at this pixel: min with the material's
    // (Lagarde & de Rousiers 2014, 4.10.3), and the bent normal for the irradiance. Not in the
    // opaque frame behind transmissive surfaces, whose pixels the view buffers give to them.
    vec4 ao = texelFetch(screenOcclusion, ivec2(gl_FragCoord.xy), 0);
    surface.material.occlusion = min(surface.material.occlusion, ao.x);
    // The pixel's bent normal, unless it is another surface's (an edge, with multisampling).
    if (dot(ao.yzw, surface.normal) > 0.0) bentNormal = ao.yzw;
  }
  // The screen-space reflection (view/ssr.frag), in the second pass of a frame that has them.
  vec4 reflection = draw.scenePass == 2
                        ? texelFetch(screenReflection, ivec2(gl_FragCoord.xy), 0)
                        : vec4(0.0);
  vec3 color = shadeSplitSum(surface.position, gl_FragCoord.xy, surface.normal, surface.view,
                             surface.material, surface.sheen, bentNormal, reflection);
  // An area light between the camera and the surface is what the pixel sees; not in the lit
  // frame of the screen-space reflections, whose rays meet the surfaces of the view buffers, nor
  // in the opaque frame behind transmissive surfaces (lit as that one).
  Ray center = primaryRay(gl_FragCoord.xy);
  vec3 emitted;
  bool isSurface;
  if ((draw.scenePass == 0 || draw.scenePass == 2) &&
      nearestEmitter(center, gl_FragCoord.xy,
                     dot(surface.position - center.origin, center.direction), emitted, isSurface))
    color = emitted;
  outColor = vec4(color, 1.0);
}
