#pragma once
// Linear sRGB (D65) from CIE XYZ, and the sRGB transfer function for previews.
#include <array>

namespace kasha {

using Vec3d = std::array<double, 3>;

// IEC 61966-2-1 matrices at full precision, derived from the sRGB primaries and D65 white
// (host/data/sRGB_XYZ_constants.txt).
Vec3d xyz_to_linear_srgb(const Vec3d& xyz);
Vec3d linear_srgb_to_xyz(const Vec3d& rgb);
double srgb_encode(double linear);  // linear in [0,1] -> encoded value in [0,1]
// Chromaticity (x, y); (0, 0) for black.
std::array<double, 2> chromaticity(const Vec3d& xyz);

}  // namespace kasha
