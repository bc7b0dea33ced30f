#include "geometry/instances.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>

namespace kasha {

Affine inverse_affine(const Affine& m) {
  Eigen::Matrix4d a = Eigen::Matrix4d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) a(r, c) = m[4 * r + c];
  const Eigen::Matrix4d inv = a.inverse();
  Affine out{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) out[4 * r + c] = inv(r, c);
  return out;
}

std::array<float, 6> object_box(const std::vector<KTriangle>& triangles, const ObjectRange& r) {
  std::array<float, 6> b = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
  for (int i = r.first_triangle; i < r.first_triangle + r.triangle_count; ++i)
    for (const float* v : {triangles[i].v0, triangles[i].v1, triangles[i].v2})
      for (int c = 0; c < 3; ++c) b[c] = std::min(b[c], v[c]), b[3 + c] = std::max(b[3 + c], v[c]);
  return b;
}

void affine_point(const float* m, const float* p, float* out) {
  for (int r = 0; r < 3; ++r)
    out[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
}

void affine_direction(const float* m, const float* d, float* out) {
  for (int r = 0; r < 3; ++r) out[r] = m[4 * r] * d[0] + m[4 * r + 1] * d[1] + m[4 * r + 2] * d[2];
}

KInstance kernel_instance(const Placement& p) {
  KInstance k{};
  const Affine inv = inverse_affine(p.world_from_object);
  for (int i = 0; i < 12; ++i) {
    k.world_from_object[i] = static_cast<float>(p.world_from_object[i]);
    k.object_from_world[i] = static_cast<float>(inv[i]);
  }
  k.object = p.object;
  const Eigen::Matrix3d linear =
      Eigen::Map<const Eigen::Matrix<double, 3, 4, Eigen::RowMajor>>(p.world_from_object.data())
          .leftCols<3>();
  k.mirrors = linear.determinant() < 0 ? 1 : 0;
  return k;
}

std::vector<KInstance> kernel_instances(const SceneInstances& instances) {
  std::vector<KInstance> out;
  if (instances.empty()) return out;
  if (instances.world_triangles > 0) {
    Placement own;
    own.object = -1;
    own.world_from_object = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    out.push_back(kernel_instance(own));
  }
  for (const Placement& p : instances.placements) out.push_back(kernel_instance(p));
  return out;
}

KTriangle placed_triangle(const KTriangle& t, const KInstance& instance) {
  KTriangle w = t;
  affine_point(instance.world_from_object, t.v0, w.v0);
  affine_point(instance.world_from_object, t.v1, w.v1);
  affine_point(instance.world_from_object, t.v2, w.v2);
  if (instance.mirrors) std::swap(w.v1, w.v2);
  return w;
}

}  // namespace kasha
