#pragma once
// What `kasha measure` produces: a material's three parts on the measurement's own wavelengths,
// the diagnostics written beside them, and the matrices its plots show.
#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "material/material.h"
#include "measure/eem.h"

namespace kasha {

struct Tabulated {
  std::vector<double> nm, value;
};

struct MeasuredMaterial {
  Tabulated passive;     // ρ(λ)
  Tabulated excitation;  // a(λ), an energy yield
  Tabulated emission;    // e(λ), Σ e Δλ = 1
  std::optional<GlossDesc> gloss;

  // Diagnostics.
  std::string source;  // the measurement file the material comes from, for messages
  std::string method;  // "fluorimeter" or "bispectral"
  double band_nm = 0;  // half-width of the near-diagonal band
  bool band_estimated = false;
  double rank1_residual = 0;         // over all known entries
  double rank1_signal_residual = 0;  // over the entries that carry signal
  int second_order_masked = 0;
  double max_energy = 0, max_energy_nm = 0;  // largest g + ρ + a and where
  std::vector<double> clipped_nm;            // wavelengths clipped by --clip
  std::vector<std::string> notes;

  // For the plots: rows λo, columns λi.
  std::vector<double> ex_nm, em_nm;
  Eigen::MatrixXd raw, fluorescence, known, fit;
};

// g + ρ + a over the excitation wavelengths; without `clip` an energy gain throws kasha::Error
// naming the source file and the wavelength, with it ρ (then a) is reduced to fit and the
// wavelength recorded.
void check_energy(MeasuredMaterial& m, bool clip);

// A sample without fluorescence (nothing off the band, so the fit is zero) has no emission shape
// to normalize: its fluorescence part is dropped, with a note, and the material is passive only.
void drop_zero_fluorescence(MeasuredMaterial& m);

// A material measured from the matrix `d` by `method`: its source, wavelengths and raw matrix set,
// its parts still to be found.
MeasuredMaterial measured_from(const ExcitationEmissionMatrix& d, const std::string& method);

// Linear interpolation in a tabulated function, zero outside.
double interpolate(const Tabulated& t, double nm);

}  // namespace kasha
