#pragma once
// Small meshes written in the formats kasha reads through Assimp (PLY, glTF, GLB) and as OBJ, for
// the mesh tests and the fuzz harness's seeds.
#include <array>
#include <string>
#include <vector>

namespace kasha::test {

struct TestMesh {
  std::vector<std::array<float, 3>> positions, normals;
  std::vector<std::array<float, 2>> uvs;  // v up, as kasha's
  std::vector<std::array<int, 3>> faces;
};

// Four vertices (a bent quad) and two triangles, every value exact in float.
TestMesh tent_mesh();

std::string mesh_obj(const TestMesh& m);
std::string mesh_ply(const TestMesh& m, bool binary);
// glTF's one buffer: positions, normals, texture coordinates (v down, as glTF's), 16-bit indices.
std::string mesh_gltf_buffer(const TestMesh& m);
// A glTF document whose buffer is at `uri` (empty: the GLB's own), `node_extra` added to its node.
std::string mesh_gltf(const TestMesh& m, const std::string& uri, const std::string& node_extra = "");
std::string mesh_glb(const TestMesh& m);
std::string base64(const std::string& bytes);

}  // namespace kasha::test
