#pragma once
// Internal to the glTF loader: the vertex normals and tangents a mesh lacks (glTF 2.0 3.7.2.1
// leaves them to the client), generated from its triangles and its UVs.
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "ibl/render/scene.hpp"

namespace ibl {

// Area-weighted vertex normals: each triangle's unnormalized cross product added to its three
// vertices, the sums normalized.
// @param m  the mesh: its positions and indices (three per triangle) are read.
// @return one unit normal per position; +Z for a vertex no triangle with an area touches.
std::vector<glm::vec3> generateNormals(const Mesh& m);

// Tangents from UV derivatives per triangle, accumulated and orthogonalized per vertex
// (Lengyel 2001), handedness in w.
// @param m    the mesh: its positions, indices and unit normals (one per position) are read.
// @param uvs  one UV per position: the set the normal map reads.
// @return one tangent per position: xyz unit and orthogonal to the normal, w = +1 or -1 such
//         that the bitangent is w * cross(normal, tangent).
std::vector<glm::vec4> generateTangents(const Mesh& m, const std::vector<glm::vec2>& uvs);

}  // namespace ibl
