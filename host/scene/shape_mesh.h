#pragma once
// Triangles of each scene shape type. A triangle's front is the side (v1−v0)×(v2−v0) points to;
// closed shapes face outward unless `inward`.
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace kasha {

using Triangle = std::array<Eigen::Vector3d, 3>;
// Texture coordinates (u, v) at a triangle's three vertices (docs/textures.md#texture-coordinates).
using TriangleUv = std::array<Eigen::Vector2d, 3>;

// Shading normals at a triangle's three vertices (OBJ `vn`), unit length.
using TriangleNormals = std::array<Eigen::Vector3d, 3>;

// A shape's triangles and, triangle by triangle, their texture coordinates and shading normals
// (`normals` empty when the shape has none; a face of such a shape without them gets its
// geometric normal at every vertex).
struct ShapeMesh {
  std::vector<Triangle> tris;
  std::vector<TriangleUv> uv;
  std::vector<TriangleNormals> normals;
};

// (0, 0) at the corner, u along `u`, v along `v`.
ShapeMesh quad_triangles(const Eigen::Vector3d& corner, const Eigen::Vector3d& u,
                         const Eigen::Vector3d& v);
// Each face a quad, (0, 0) to (1, 1).
ShapeMesh box_triangles(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
// A UV sphere with `segments` around the axis (+y) and segments/2 rings; u = φ/2π from +x
// towards +z, v = θ/π from +y.
ShapeMesh sphere_triangles(const Eigen::Vector3d& center, double radius, int segments);
// All faces of an OBJ file, triangulated, with their `vt` coordinates (pbrt-v4's (0, 0), (1, 0),
// (1, 1) for a face without them) and `vn` normals; throws kasha::Error naming the file on failure.
ShapeMesh obj_triangles(const std::string& path);

// Applies a transform, keeping each triangle's front side (mirroring transforms swap winding);
// normals go through the inverse transpose.
void transform_triangles(ShapeMesh& mesh, const Eigen::Affine3d& m);
void flip_triangles(ShapeMesh& mesh);

}  // namespace kasha
