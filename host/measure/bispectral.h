#pragma once
// From a measured bispectral (Donaldson) matrix D(λo, λi) — diagonal: the reflectance factor;
// off-diagonal: fluorescent re-radiation per bin — to a material. Per bin, D ≈ diag(ρ) + ê aᵀ:
// the off-diagonal entries give the rank-1 fit, whose diagonal share is subtracted from D's
// diagonal for ρ; a_i = Σ_o (ê aᵀ)_oi is the energy yield and e = ê / Δλ.
#include "measure/eem.h"
#include "measure/measured_material.h"

namespace kasha {

// band_nm <= 0: the diagonal and one bin on each side are left out of the fit.
MeasuredMaterial material_from_bispectral(const ExcitationEmissionMatrix& donaldson,
                                          double band_nm);

}  // namespace kasha
