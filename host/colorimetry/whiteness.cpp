#include "colorimetry/whiteness.h"

namespace kasha {

Whiteness cie_whiteness(const Vec3d& xyz, const Vec3d& white, Observer observer) {
  auto xy = chromaticity(xyz), n = chromaticity(white);
  const double dx = n[0] - xy[0], dy = n[1] - xy[1];
  // The tint's x coefficient is the one term that differs between the observers.
  const double tx = observer == Observer::cie1964_10deg ? 900 : 1000;
  Whiteness r;
  r.w = xyz[1] + 800 * dx + 1700 * dy;
  r.t = tx * dx - 650 * dy;
  r.in_range = r.w > 40 && r.w < 5 * xyz[1] - 280 && r.t > -4 && r.t < 2;
  return r;
}

}  // namespace kasha
