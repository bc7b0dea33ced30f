#pragma once
// Dispersion: a dielectric's index of refraction as a function of wavelength — Sellmeier's and
// Cauchy's formulas, and named glasses by their published Sellmeier coefficients
// (docs/materials.md#dispersion).
#include <functional>
#include <string>
#include <vector>

#include "spectrum/spectrum.h"

namespace kasha {

// n(λ)² = 1 + Σ B_i λ² / (λ² − C_i), λ in µm, C_i in µm².
double sellmeier_index(const std::vector<double>& B, const std::vector<double>& C_um2, double nm);
// n(λ) = A + B / λ² + C / λ⁴, λ in µm.
double cauchy_index(double A, double B_um2, double C_um4, double nm);

// The formula as a spectrum, averaged over each bin by integration on 1 nm pieces. Where the
// formula has no real index (beyond a glass's poles) its value is NaN, and the bin check on the
// grid (discretize_material) names the wavelength.
SpectrumPtr index_spectrum(const std::function<double(double)>& index);

// A named glass ("BK7", "fused_silica", "SF11", "water"); nullptr for an unknown name.
SpectrumPtr named_glass(const std::string& name);
std::vector<std::string> named_glass_names();

}  // namespace kasha
