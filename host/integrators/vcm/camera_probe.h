#pragma once
// What vcm's host probes (merging_distance.h, seen_light.h) share: camera rays and triangle
// normals in float, as the kernels build them (kernels/geometry/camera.h,
// kernels/geometry/hit_point.h).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "shared/shared_types.h"

namespace kasha::camera_probe {

inline Eigen::Vector3f vec(const float* v) {
  return {v[0], v[1], v[2]};
}

// The geometric normal, (v1 − v0) × (v2 − v0): the triangle's front.
inline Eigen::Vector3f triangle_normal(const KTriangle& t) {
  return (vec(t.v1) - vec(t.v0)).cross(vec(t.v2) - vec(t.v0)).normalized();
}

// The camera ray through image point (sx, sy) in [−1, 1]², y up (camera_direction's).
inline Eigen::Vector3f camera_direction(const KCamera& c, float sx, float sy) {
  return (vec(c.forward) + sx * vec(c.right) + sy * vec(c.up)).normalized();
}

}  // namespace kasha::camera_probe
