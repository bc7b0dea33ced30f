#pragma once
// The fit behind RGB → spectrum (Jakob & Hanika 2019, "A Low-Dimensional Function Space for
// Efficient Spectral Upsampling"): a reflectance spectrum s(λ) = S(c0 λ² + c1 λ + c2), S the
// sigmoid ½ + x / (2√(1 + x²)) — smooth and inside (0, 1) whatever the coefficients — whose colour
// under D65 matches a linear sRGB colour, found by Gauss–Newton on the CIELAB difference. The
// build runs it over a grid of colours (host/tools/rgb_spectrum_table.cpp) and kasha looks the
// table up (spectrum/rgb_spectrum.h). Dependency-free, so the build-time tool compiles it alone.
#include <array>
#include <vector>

namespace kasha {

// The colorimetric data of the fit, sampled every `step_nm` from `min_nm`: the CIE 1931 2°
// colour-matching functions and the D65 illuminant.
struct FitObserver {
  double min_nm = 360, step_nm = 5;
  std::vector<double> x, y, z, d65;
};

// The table's size per axis and the scale of its z axis (its brightest component), denser near 0
// and 1: smoothstep(smoothstep(k / (res − 1))).
constexpr int kRgbTableRes = 64;
double rgb_table_scale(int k, int res = kRgbTableRes);

// The other two axes: the ratio of a component to the largest, sin²(π/2 · i/(res − 1)), dense
// near 0, where saturated colours change fastest, and near 1, towards white (pbrt-v4's table is
// linear; this one keeps the round trip within ΔE2000 0.5 at the sRGB primaries), and the
// (fractional) index of a ratio.
double rgb_table_ratio(int i, int res = kRgbTableRes);
double rgb_table_ratio_index(double ratio, int res = kRgbTableRes);

// Coefficients (c0, c1, c2) for λ in nm.
using SigmoidCoefficients = std::array<double, 3>;
double sigmoid_spectrum(const SigmoidCoefficients& c, double nm);

// The whole table: [3 (which component is largest)][res (z)][res (y)][res (x)][3 coefficients],
// as pbrt-v4's rgb2spec_opt lays it out; at index (l, k, j, i) the colour whose component l is
// scale(k) and components l+1 and l+2 (mod 3) are ratio(i) and ratio(j) of it.
std::vector<float> fit_rgb_table(const FitObserver& obs, int res = kRgbTableRes);

// The CIELAB colour (D65 white) of the reflectance c under D65, and of a linear sRGB colour.
std::array<double, 3> fit_spectrum_lab(const FitObserver& obs, const SigmoidCoefficients& c);
std::array<double, 3> fit_rgb_lab(const std::array<double, 3>& rgb);

}  // namespace kasha
