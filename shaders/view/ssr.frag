#version 450
// Screen-space reflections of the viewer: the stochastic trace of
// ibl/shared/screen_space_reflections.h (which the CPU's split sum runs too; Lagarde & de Rousiers
// 2014, 4.9.4; Stachowiak 2015) at each pixel, through the view buffers (view/view_buffers.frag)
// and the frame's first, unreflected pass (the lit frame). Writes the premultiplied reflection and
// the share of the lobe it holds, which the resolve (view/ssr_resolve.frag) shares between
// neighbors for the scene's second pass (view/scene.frag).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "view/frame.glsl"
#include "view/ssr_buffers.glsl"
layout(location = 0) out vec4 outReflection;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  outReflection = screenSpaceReflection(frameScreenProjection(), pixel, ssrRoughness(pixel),
                                        frameReflectionParameters());
}
