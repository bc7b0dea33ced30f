#include "scene/sphere_light.h"

#include <algorithm>
#include <cmath>

namespace kasha {

std::optional<SphereBound> tessellated_sphere(const ShapeMesh& mesh, const SphereBound& own,
                                              const Eigen::Affine3d& placed) {
  if (mesh.tris.empty() || !(own.radius > 0)) return std::nullopt;
  const Eigen::Vector3d c = placed * own.centre;
  double lo = INFINITY, hi = 0;
  for (const Triangle& t : mesh.tris) {
    for (const Eigen::Vector3d& v : t) {
      const double d = (v - c).norm();
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    // A front facing the centre (an inward sphere) is seen from inside, where a cone of
    // directions from outside finds nothing.
    const Eigen::Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
    if (n.dot((t[0] + t[1] + t[2]) / 3 - c) < 0) return std::nullopt;
  }
  if (!(hi > 0) || hi - lo > 1e-6 * hi) return std::nullopt;
  return SphereBound{c, hi};
}

}  // namespace kasha
