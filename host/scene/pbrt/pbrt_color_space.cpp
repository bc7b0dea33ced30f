#include "scene/pbrt/pbrt_color_space.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cctype>

namespace kasha {

namespace {

const PbrtColorSpace kSpaces[] = {
    {"srgb", {0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.3290}},
    {"dci-p3", {0.68, 0.32}, {0.265, 0.690}, {0.15, 0.06}, {0.3127, 0.3290}},
    {"rec2020", {0.708, 0.292}, {0.170, 0.797}, {0.131, 0.046}, {0.3127, 0.3290}},
    // The ACES white is its D60 illuminant's (SMPTE ST 2065-1).
    {"aces2065-1", {0.7347, 0.2653}, {0.0, 1.0}, {0.0001, -0.077}, {0.32168, 0.33767}},
};

Eigen::Vector3d xyz_of(const std::array<double, 2>& xy) {
  return {xy[0] / xy[1], 1, (1 - xy[0] - xy[1]) / xy[1]};
}

// RGB → XYZ: the primaries' XYZ scaled so that RGB (1, 1, 1) is the white at Y = 1.
Eigen::Matrix3d rgb_to_xyz(const PbrtColorSpace& s) {
  Eigen::Matrix3d p;
  p << xyz_of(s.r), xyz_of(s.g), xyz_of(s.b);
  const Eigen::Vector3d scale = p.colPivHouseholderQr().solve(xyz_of(s.white));
  return p * scale.asDiagonal();
}

// Bradford's chromatic adaptation from white `from` to white `to` (XYZ → XYZ).
Eigen::Matrix3d bradford(const std::array<double, 2>& from, const std::array<double, 2>& to) {
  Eigen::Matrix3d m;
  m << 0.8951, 0.2664, -0.1614, -0.7502, 1.7135, 0.0367, 0.0389, -0.0685, 1.0296;
  const Eigen::Vector3d a = m * xyz_of(from), b = m * xyz_of(to);
  return m.inverse() * b.cwiseQuotient(a).asDiagonal() * m;
}

}  // namespace

const PbrtColorSpace* pbrt_color_space(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  for (const PbrtColorSpace& s : kSpaces)
    if (lower == s.name) return &s;
  return nullptr;
}

std::array<double, 3> pbrt_rgb_to_srgb(const PbrtColorSpace& space,
                                       const std::array<double, 3>& rgb, bool adapt) {
  const PbrtColorSpace& srgb = kSpaces[0];
  Eigen::Matrix3d m = rgb_to_xyz(space);
  if (adapt) m = bradford(space.white, srgb.white) * m;
  const Eigen::Vector3d out =
      rgb_to_xyz(srgb).inverse() * m * Eigen::Vector3d(rgb[0], rgb[1], rgb[2]);
  return {out[0], out[1], out[2]};
}

}  // namespace kasha
