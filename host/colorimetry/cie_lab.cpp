#include "colorimetry/cie_lab.h"

#include <cmath>

namespace kasha {

// The CIE cube root with its linear segment below (6/29)³, so dark colours stay finite-sloped.
static double lab_f(double t) {
  constexpr double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

Vec3d xyz_to_lab(const Vec3d& xyz, const Vec3d& white) {
  double fx = lab_f(xyz[0] / white[0]), fy = lab_f(xyz[1] / white[1]),
         fz = lab_f(xyz[2] / white[2]);
  return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

}  // namespace kasha
