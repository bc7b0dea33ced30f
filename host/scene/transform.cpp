#include "scene/transform.h"

#include <cmath>

namespace kasha {

Eigen::Affine3d parse_transform(const JsonNode& node) {
  Eigen::Affine3d m = Eigen::Affine3d::Identity();
  if (auto matrix = node.find("matrix")) {
    std::vector<double> v = matrix->numbers();
    if (v.size() != 16) matrix->fail("expected 16 numbers (a row-major 4x4 matrix)");
    if (node.has("translate") || node.has("rotate") || node.has("scale"))
      node.fail("\"matrix\" cannot be combined with translate, rotate or scale");
    Eigen::Matrix4d full;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) full(r, c) = v[4 * r + c];
    if (full(3, 0) != 0 || full(3, 1) != 0 || full(3, 2) != 0 || full(3, 3) != 1)
      matrix->fail("the last row must be [0, 0, 0, 1] (no projective transforms)");
    m.matrix() = full;
  } else {
    if (auto scale = node.find("scale")) {
      Eigen::Vector3d s;
      if (scale->is_number())
        s.setConstant(scale->number());
      else {
        auto a = scale->vec3();
        s = {a[0], a[1], a[2]};
      }
      m.prescale(s);
    }
    if (auto rotate = node.find("rotate")) {
      auto axis = rotate->at("axis").vec3();
      Eigen::Vector3d ax(axis[0], axis[1], axis[2]);
      if (ax.norm() == 0) rotate->fail("rotation axis is zero");
      double deg = rotate->at("deg").number();
      rotate->finish();
      m.prerotate(Eigen::AngleAxisd(deg * M_PI / 180.0, ax.normalized()));
    }
    if (auto translate = node.find("translate")) {
      auto t = translate->vec3();
      m.pretranslate(Eigen::Vector3d(t[0], t[1], t[2]));
    }
  }
  node.finish();
  if (std::abs(m.linear().determinant()) < 1e-300) node.fail("transform is singular");
  return m;
}

}  // namespace kasha
