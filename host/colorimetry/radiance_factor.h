#pragma once
// The total radiance factor of a Lambertian fluorescent surface under a lamp of spectral radiance S
// (CIE 15:2004 §9, CIE 182): β(λ) = β_R + β_L = ρ(λ) + ê(λ)·Σ_i a(λ_i)S(λ_i) / S(λ), per bin. It
// depends on the lamp, unlike a plain reflectance: the fluorescent part is light moved from the
// lamp's excitation band into the emission band.
#include <vector>

#include "material/material.h"

namespace kasha {

// Below this fraction of the lamp's peak a bin counts as unlit: where the surface fluoresces into
// an unlit bin, β_L is undefined (NaN).
constexpr double kUnlitFraction = 1e-6;

struct RadianceFactor {
  std::vector<double> reflected;    // β_R = ρ
  std::vector<double> fluorescent;  // β_L, NaN where it emits into an unlit bin
  // β_R + β_L (NaN where β_L is).
  std::vector<double> total() const;
};

// The spectral radiance leaving the surface when the whole hemisphere above it has radiance
// `lamp` (per bin): ρ_j S_j + ê_j Σ_i a_i S_i, i.e. (diag ρ + ê aᵀ) S. Defined everywhere.
std::vector<double> leaving_radiance(const Material& material, const std::vector<double>& lamp);

RadianceFactor radiance_factor(const Material& material, const std::vector<double>& lamp);

}  // namespace kasha
