#pragma once
// CIE 1931 2° colour-matching functions averaged over the bins of a grid.
#include <array>
#include <vector>

#include "spectrum/wavelength_grid.h"

namespace kasha {

struct BinnedObserver {
  std::vector<double> x, y, z;  // x̄ȳz̄ averaged over each bin

  explicit BinnedObserver(const WavelengthGrid& grid);
  // XYZ = Σ_i cmf_i · L_i · Δλ (no 683 factor, as pbrt-v4's film).
  std::array<double, 3> xyz(const std::vector<double>& per_bin, double bin_nm) const;
};

// The continuous colour-matching functions (piecewise linear through the 1 nm CIE table).
const std::array<SpectrumPtr, 3>& cie_1931_cmf();

}  // namespace kasha
