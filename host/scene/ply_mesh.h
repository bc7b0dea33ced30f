#pragma once
// PLY meshes read as pbrt-v4 reads them (util/mesh.cpp TriQuadMesh::ReadPLY through rply, whose
// rules are the specification; docs/formats.md#mesh-files): kasha's own reader, because Assimp's
// skips whitespace after `end_header` and so reads a binary file whose first data byte is 0x0A one
// byte off. ASCII and both binary byte orders; every rply type and alias; vertex x/y/z, nx/ny/nz
// and texture coordinates named u/v, s/t, texture_u/texture_v or texture_s/texture_t; faces of 3
// and 4 vertices (a quad split as pbrt-v4's ConvertToOnlyTriangles splits it); other elements and
// properties skipped. Every count is checked against the bytes that remain before anything is
// allocated.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "scene/shape_mesh.h"

namespace kasha {

// The file's content, indexed as pbrt-v4 holds it.
struct PlyMesh {
  std::vector<Eigen::Vector3d> p;
  std::vector<Eigen::Vector3d> n;   // empty: the file has no nx/ny/nz
  std::vector<Eigen::Vector2d> uv;  // empty: the file has no texture coordinates
  std::vector<int> tris;            // 3 per triangle
  std::vector<int> quads;           // 4 per quad, in pbrt-v4's bilinear order: face 0 1 3 2
  // pbrt-v4 reads `face_indices` for Ptex textures alone; kasha has none, so it is checked and
  // kept, and nothing uses it.
  std::vector<int> face_indices;
  long skipped_faces = 0;  // faces of other than 3 or 4 vertices (pbrt-v4 warns and skips them)
};

// Parses PLY `bytes`; `path` names the file in messages. Throws kasha::Error "PATH: why".
PlyMesh parse_ply(const std::string& bytes, const std::string& path);

// The triangles of a parsed mesh (quads as two triangles, pbrt-v4's (0, 0), (1, 0), (1, 1) where
// there are no texture coordinates, unit shading normals where there are normals).
ShapeMesh ply_mesh_triangles(const PlyMesh& mesh, const std::string& path);

}  // namespace kasha
