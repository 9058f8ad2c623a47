#version 450
// Cube map -> cube: resample_to_cube.glsl for a cube level.
#extension GL_GOOGLE_include_directive : require
#define CUBE_SOURCE 1
#include "ibl/shared/cube.h"
#include "env/resample_to_cube.glsl"
