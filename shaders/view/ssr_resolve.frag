#version 450
// The resolve of the screen-space reflections (resolveScreenReflection of
// ibl/shared/screen_space_reflections.h, as the CPU's): glossy pixels share their neighbors'
// traced reflections (view/ssr.frag), for the scene's second pass (view/scene.frag).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "view/frame.glsl"
#include "view/ssr_buffers.glsl"
layout(location = 0) out vec4 outReflection;

void main() {
  outReflection = resolveScreenReflection(frameScreenProjection(), ivec2(gl_FragCoord.xy),
                                          frameReflectionParameters());
}
