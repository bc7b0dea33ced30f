#pragma once
// The CIEDE2000 colour difference (CIE 142-2001), as worked out by Sharma, Wu and Dalal, "The
// CIEDE2000 color-difference formula: implementation notes, supplementary test data, and
// mathematical observations", Color Res. Appl. 30 (2005) — including their hue-angle conventions.
#include "color/color_space.h"

namespace kasha {

double ciede2000(const Vec3d& lab1, const Vec3d& lab2, double kL = 1, double kC = 1, double kH = 1);

}  // namespace kasha
