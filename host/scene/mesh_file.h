#pragma once
// Mesh files through Assimp (docs/formats.md#mesh-files): PLY (ASCII and binary), glTF 2.0
// (.gltf with its buffers, .glb) and OBJ. Every triangle of every mesh in the file, with the
// file's node transforms applied, its first set of texture coordinates and its normals (as
// shading normals) where it has them; points and lines are dropped.
#include <string>

#include "scene/shape_mesh.h"

namespace kasha {

// Throws kasha::Error "FILE: why" for an unknown format, a file Assimp cannot read, or one that
// names a buffer outside its own folder.
ShapeMesh mesh_file_triangles(const std::string& path);

}  // namespace kasha
