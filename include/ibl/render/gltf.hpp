#pragma once
// glTF 2.0 scenes for the renderer and the viewer.
#include <string>

#include "ibl/render/scene.hpp"

namespace ibl {

// Reads a glTF 2.0 file (.gltf with external or embedded buffers, .glb), applying node
// transforms; KHR_draco_mesh_compression primitives are decoded; missing normals and tangents
// are generated. Throws Error("<path>: ...") for anything it cannot read.
Scene loadGltf(const std::string& path);

}  // namespace ibl
