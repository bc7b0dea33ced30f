#include "scene/triangle_dpdu.h"

#include <cmath>

namespace kasha {

Eigen::Vector3d triangle_dpdu(const Triangle& p, const TriangleUv& uv) {
  const Eigen::Vector2d duv02 = uv[0] - uv[2], duv12 = uv[1] - uv[2];
  const Eigen::Vector3d dp02 = p[0] - p[2], dp12 = p[1] - p[2];
  const double det = duv02.x() * duv12.y() - duv02.y() * duv12.x();
  if (std::abs(det) >= 1e-9) {
    const Eigen::Vector3d dpdu = (duv12.y() * dp02 - duv02.y() * dp12) / det;
    const Eigen::Vector3d dpdv = (duv02.x() * dp12 - duv12.x() * dp02) / det;
    if (dpdu.cross(dpdv).squaredNorm() > 0) return dpdu;
  }
  const Eigen::Vector3d ng = (p[2] - p[0]).cross(p[1] - p[0]);
  if (!(ng.squaredNorm() > 0)) return Eigen::Vector3d::Zero();
  // pbrt-v4's CoordinateSystem (Duff et al. 2017): its first tangent.
  const Eigen::Vector3d n = ng.normalized();
  const double sign = std::copysign(1.0, n.z()), a = -1 / (sign + n.z()), b = n.x() * n.y() * a;
  return {1 + sign * n.x() * n.x() * a, sign * b, -sign * n.x()};
}

}  // namespace kasha
