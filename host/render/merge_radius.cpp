#include "render/merge_radius.h"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "core/warning.h"

namespace kasha {

MergeRadiusBounds merge_radius_bounds(const Scene& scene, const KCamera& c) {
  MergeRadiusBounds b;
  b.footprint =
      2.0 * std::sqrt(c.up[0] * c.up[0] + c.up[1] * c.up[1] + c.up[2] * c.up[2]) / c.height;
  Eigen::Vector3d centre;
  double radius;
  scene.bounding_sphere(centre, radius);  // its diameter is the triangles' box's diagonal
  b.largest = 2 * radius / 50;
  const Eigen::Vector3d eye(c.position[0], c.position[1], c.position[2]);
  b.centre_distance = (centre - eye).norm();
  return b;
}

void warn_radius_beyond(double radius, const MergeRadiusBounds& bounds) {
  warn("--radius " + std::to_string(radius) + " is beyond 1/50 of the scene's diagonal; using " +
       std::to_string(bounds.largest));
}

}  // namespace kasha
