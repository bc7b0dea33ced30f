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
  Eigen::AlignedBox3d box;
  for (const KTriangle& t : scene.triangles)
    for (const float* v : {t.v0, t.v1, t.v2}) box.extend(Eigen::Vector3d(v[0], v[1], v[2]));
  b.largest = box.diagonal().norm() / 50;
  const Eigen::Vector3d eye(c.position[0], c.position[1], c.position[2]);
  b.centre_distance = (box.center() - eye).norm();
  return b;
}

void warn_radius_beyond(double radius, const MergeRadiusBounds& bounds) {
  warn("--radius " + std::to_string(radius) + " is beyond 1/50 of the scene's diagonal; using " +
       std::to_string(bounds.largest));
}

}  // namespace kasha
