#include "color/color_space.h"

#include <algorithm>
#include <cmath>

#include "shared/color_constants.h"

namespace kasha {

static Vec3d apply(const double m[3][3], const Vec3d& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
          m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

Vec3d xyz_to_linear_srgb(const Vec3d& xyz) {
  static const double m[3][3] = KASHA_XYZ_TO_SRGB;
  return apply(m, xyz);
}

Vec3d linear_srgb_to_xyz(const Vec3d& rgb) {
  static const double m[3][3] = KASHA_SRGB_TO_XYZ;
  return apply(m, rgb);
}

double srgb_encode(double l) {
  l = std::clamp(l, 0.0, 1.0);
  return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
}

std::array<double, 2> chromaticity(const Vec3d& xyz) {
  double s = xyz[0] + xyz[1] + xyz[2];
  if (s <= 0) return {0, 0};
  return {xyz[0] / s, xyz[1] / s};
}

}  // namespace kasha
