#pragma once
// CIE 1976 L*a*b* (CIELAB) from XYZ relative to a reference white (CIE 15:2004 §8.2.1).
#include "color/color_space.h"

namespace kasha {

Vec3d xyz_to_lab(const Vec3d& xyz, const Vec3d& white);

}  // namespace kasha
