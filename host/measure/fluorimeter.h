#pragma once
// From a fluorimeter's excitation–emission matrices of a sample and of a white diffuse reference
// (the etalon) to a material, by the corrected equations of docs/measurement.md#the-equations:
//   ρ(λi)       = ρ_e(λi) · (R̄(λi) − fluorescence inside the band) / R̄_e(λi)
//   f^f(λo, λi) = f_e(λi) · R(λo; λi) / R̄_e(λi) · C(λi)/C(λo),   |λo − λi| > ε
//   a(λi)       = π ∫ f^f dλo,   e(λo) the emission shape, from the best non-negative rank-1 fit.
#include "measure/eem.h"
#include "measure/measured_material.h"
#include "spectrum/spectrum.h"

namespace kasha {

struct FluorimeterInput {
  ExcitationEmissionMatrix sample, etalon;
  SpectrumPtr etalon_reflectance;  // ρ_e
  SpectrumPtr sensitivity;         // C(λ), or null when the instrument already corrects for it
  double band_nm = 0;              // ε; <= 0: found from the etalon's diagonal peak
  // The files the two spectra come from, for messages.
  std::string etalon_reflectance_source = "--etalon-reflectance",
              sensitivity_source = "--sensitivity";
};

MeasuredMaterial material_from_fluorimeter(const FluorimeterInput& in);

// The band half-width the etalon's diagonal peak shows: where it falls below 2 % of its top,
// over the excitation wavelengths inside the emission range, plus one emission sample of margin.
double band_from_etalon(const ExcitationEmissionMatrix& etalon);

// Refuses a band half-width that is not positive and narrower than the emission range (no reading
// would lie outside it). `estimated_from`: the etalon when the band was estimated, else empty and
// the message names --band-nm.
void check_band(const ExcitationEmissionMatrix& m, double band_nm,
                const std::string& estimated_from);

// Quadrature weights of a sampled function over its wavelengths (trapezoid rule).
std::vector<double> trapezoid_weights(const std::vector<double>& nm);

}  // namespace kasha
