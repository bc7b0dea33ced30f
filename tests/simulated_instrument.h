#pragma once
// A simulated fluorimeter with known answers, for testing `kasha measure`: excitation and
// emission monochromator band-passes, a lamp with a line, a detector sensitivity, shot and read
// noise, and the grating's second-order peaks near λo = 2λi.
#include <functional>
#include <random>

#include "measure/eem.h"

namespace kasha::test {

using SpectralFunction = std::function<double(double)>;

struct TrueMaterial {
  SpectralFunction rho;         // passive reflectance
  SpectralFunction excitation;  // a(λ), energy yield
  SpectralFunction emission;    // e(λ), ∫ e dλ = 1
  // A second fluorophore (for the rank-1 check); null for one.
  SpectralFunction excitation2, emission2;
};

struct Instrument {
  std::vector<double> ex_nm, em_nm;
  double excitation_fwhm_nm = 8, emission_fwhm_nm = 3;
  SpectralFunction lamp;         // I(λi), with a line
  SpectralFunction sensitivity;  // C(λo); constant 1 for an instrument that corrects for it
  double shot_noise = 1e-5;      // σ² = shot_noise · reading · etalon peak: 0.3 % at the peak
  double read_noise = 1e-5;      // absolute, relative to the etalon's peak
  double second_order = 0.03;    // fraction of the reflected light seen again at 2λi
  unsigned seed = 1;

  static Instrument typical(bool with_sensitivity);
  // The typical instrument with the excitation scanned over 300–780 nm, so that the passive
  // reflectance covers the visible range (how scenes/materials/brightened_paper.json was measured).
  static Instrument visible_scan();
  ExcitationEmissionMatrix measure(const TrueMaterial& m, const SpectralFunction& etalon_rho,
                                   const std::string& name) const;
};

// The material `kasha measure` is tested on: a paper with an optical brightener (excited in the
// UV, emitting blue), and the white etalon it is measured against.
TrueMaterial brightened_paper();
SpectralFunction etalon_rho();

// Writes what the instrument measures of `truth` (s.csv) and of the etalon (e.csv), the etalon's
// reflectance (rho.csv) and the detector's sensitivity (c.csv) into `dir`; returns the matching
// `kasha measure` options.
std::string write_instrument_files(const std::string& dir, const Instrument& in,
                                   const TrueMaterial& truth);

double gaussian(double x, double center, double fwhm);
// A normalized gaussian emission (∫ = 1).
SpectralFunction emission_gaussian(double center, double fwhm);
// Writes an EEM in the CSV layout of docs/formats.md#measurement-csv
void write_eem_csv(const std::string& path, const ExcitationEmissionMatrix& m);

}  // namespace kasha::test
