#pragma once
// CIE standard colorimetric observers (1931 2°, 1964 10°) averaged over the bins of a grid.
#include <array>
#include <string>
#include <vector>

#include "spectrum/wavelength_grid.h"

namespace kasha {

enum class Observer { cie1931_2deg, cie1964_10deg };

std::string observer_name(Observer observer);  // "CIE 1931 2°" or "CIE 1964 10°"

struct BinnedObserver {
  std::vector<double> x, y, z;  // x̄ȳz̄ averaged over each bin

  explicit BinnedObserver(const WavelengthGrid& grid, Observer observer = Observer::cie1931_2deg);
  // XYZ = Σ_i cmf_i · L_i · Δλ (no 683 factor, as pbrt-v4's film).
  std::array<double, 3> xyz(const std::vector<double>& per_bin, double bin_nm) const;
};

// The continuous colour-matching functions (piecewise linear through the 1 nm CIE table).
const std::array<SpectrumPtr, 3>& cie_cmf(Observer observer);

}  // namespace kasha
