#pragma once
// Triangles of each scene shape type. A triangle's front is the side (v1−v0)×(v2−v0) points to;
// closed shapes face outward unless `inward`.
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace kasha {

using Triangle = std::array<Eigen::Vector3d, 3>;

std::vector<Triangle> quad_triangles(const Eigen::Vector3d& corner, const Eigen::Vector3d& u,
                                     const Eigen::Vector3d& v);
std::vector<Triangle> box_triangles(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
// A UV sphere with `segments` around the axis and segments/2 rings.
std::vector<Triangle> sphere_triangles(const Eigen::Vector3d& center, double radius, int segments);
// All faces of an OBJ file, triangulated; throws kasha::Error naming the file on failure.
std::vector<Triangle> obj_triangles(const std::string& path);

// Applies a transform, keeping each triangle's front side (mirroring transforms swap winding).
void transform_triangles(std::vector<Triangle>& tris, const Eigen::Affine3d& m);
void flip_triangles(std::vector<Triangle>& tris);

}  // namespace kasha
