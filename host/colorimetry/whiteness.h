#pragma once
// CIE whiteness W and tint T (CIE 15:2004 §9.4; ISO 11475 uses the 10° form under D65).
#include "color/cie_observer.h"
#include "color/color_space.h"

namespace kasha {

struct Whiteness {
  double w = 0, t = 0;
  // Within CIE 15's limits of use: 40 < W < 5Y − 280 and −4 < T < 2 ("commercially white").
  bool in_range = false;
};

// `xyz` of the sample and `white` of the perfect diffuser under the same illuminant and observer
// (Y of the white = 100). CIE defines the formulas for D65; under another illuminant they are the
// same expressions about that illuminant's white point.
Whiteness cie_whiteness(const Vec3d& xyz, const Vec3d& white, Observer observer);

}  // namespace kasha
