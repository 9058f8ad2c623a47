#version 450
// Equirect -> cube: resample_to_cube.glsl for a panorama.
#extension GL_GOOGLE_include_directive : require
#define CUBE_SOURCE 0
#include "ibl/shared/cube.h"
#include "env/resample_to_cube.glsl"
