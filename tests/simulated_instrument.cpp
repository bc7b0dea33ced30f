#include "simulated_instrument.h"

#include <cmath>
#include <fstream>

namespace kasha::test {

double gaussian(double x, double center, double fwhm) {
  double s = fwhm / (2 * std::sqrt(2 * std::log(2.0)));
  return std::exp(-0.5 * (x - center) * (x - center) / (s * s));
}

SpectralFunction emission_gaussian(double center, double fwhm) {
  double s = fwhm / (2 * std::sqrt(2 * std::log(2.0)));
  return [=](double l) { return gaussian(l, center, fwhm) / (s * std::sqrt(2 * M_PI)); };
}

TrueMaterial brightened_paper() {
  TrueMaterial m;
  m.rho = [](double l) { return 0.15 + 0.65 / (1 + std::exp(-(l - 420) / 15)); };
  m.excitation = [](double l) { return 0.3 * gaussian(l, 370, 60); };
  m.emission = emission_gaussian(445, 50);
  return m;
}

SpectralFunction etalon_rho() {
  return [](double l) { return 0.97 + 0.02 * (l - 300) / 500; };
}

std::string write_instrument_files(const std::string& d, const Instrument& in,
                                   const TrueMaterial& truth) {
  write_eem_csv(d + "/s.csv", in.measure(truth, nullptr, "s.csv"));
  write_eem_csv(d + "/e.csv", in.measure(TrueMaterial{}, etalon_rho(), "e.csv"));
  std::ofstream rho(d + "/rho.csv"), c(d + "/c.csv");
  rho << "nm,rho\n";
  c << "nm,sensitivity\n";
  for (double l = 250; l <= 850; l += 5) {
    rho << l << "," << etalon_rho()(l) << "\n";
    c << l << "," << in.sensitivity(l) << "\n";
  }
  return "--sample " + d + "/s.csv --etalon " + d + "/e.csv --etalon-reflectance " + d +
         "/rho.csv --sensitivity " + d + "/c.csv";
}

Instrument Instrument::typical(bool with_sensitivity) {
  Instrument in;
  for (double l = 300; l <= 600 + 1e-9; l += 5) in.ex_nm.push_back(l);
  for (double l = 300; l <= 800 + 1e-9; l += 2) in.em_nm.push_back(l);
  // A smooth xenon-like continuum with a strong line at 467 nm.
  in.lamp = [](double l) { return 0.4 + l / 600.0 + 3.0 * gaussian(l, 467, 4); };
  in.sensitivity = with_sensitivity
                       ? SpectralFunction([](double l) { return 1.2 - 0.9 * (l - 300) / 500; })
                       : SpectralFunction([](double) { return 1.0; });
  return in;
}

Instrument Instrument::visible_scan() {
  Instrument in = typical(true);
  in.ex_nm.clear();
  for (double l = 300; l <= 780 + 1e-9; l += 5) in.ex_nm.push_back(l);
  return in;
}

ExcitationEmissionMatrix Instrument::measure(const TrueMaterial& m,
                                             const SpectralFunction& etalon_rho,
                                             const std::string& name) const {
  const size_t n_o = em_nm.size(), n_i = ex_nm.size();
  const double s1 = excitation_fwhm_nm / (2 * std::sqrt(2 * std::log(2.0)));
  const double f1_integral = s1 * std::sqrt(2 * M_PI);
  const bool etalon = !m.excitation;
  // Light leaving the sample at the detector's input, on a fine grid, before the emission
  // monochromator: reflection spread by the excitation band-pass, plus fluorescence excited by
  // all of it (docs/measurement.md#the-equations, paper eq. 5–6), plus the grating's second order.
  const double fine = 0.5;
  std::vector<double> grid;
  for (double l = em_nm.front() - 20; l <= em_nm.back() + 20; l += fine) grid.push_back(l);
  ExcitationEmissionMatrix out;
  out.source = name;
  out.ex_nm = ex_nm;
  out.em_nm = em_nm;
  out.value.resize(n_o, n_i);
  std::mt19937 rng(seed + (etalon ? 1000 : 0));
  std::normal_distribution<double> normal(0.0, 1.0);
  double etalon_peak = 0;
  for (size_t i = 0; i < n_i; ++i) etalon_peak = std::max(etalon_peak, lamp(ex_nm[i]) * 1.0 / M_PI);

  for (size_t i = 0; i < n_i; ++i) {
    const double li = ex_nm[i];
    const double rho = etalon ? etalon_rho(li) : m.rho(li);
    std::vector<double> light(grid.size());
    for (size_t k = 0; k < grid.size(); ++k) {
      double lo = grid[k];
      double reflected = gaussian(lo, li, excitation_fwhm_nm) * rho / M_PI;
      double fluorescent = 0;
      if (!etalon) {
        fluorescent = f1_integral * m.emission(lo) * m.excitation(li) / M_PI;
        if (m.excitation2) fluorescent += f1_integral * m.emission2(lo) * m.excitation2(li) / M_PI;
      }
      double second = second_order * gaussian(lo / 2, li, excitation_fwhm_nm) * rho / M_PI;
      light[k] = lamp(li) * (reflected + fluorescent + second);
    }
    for (size_t o = 0; o < n_o; ++o) {
      // The emission monochromator's band-pass (normalized), then the detector.
      double sum = 0, norm = 0;
      for (size_t k = 0; k < grid.size(); ++k) {
        double b = gaussian(grid[k], em_nm[o], emission_fwhm_nm);
        sum += b * light[k];
        norm += b;
      }
      double reading = sensitivity(em_nm[o]) * sum / norm;
      double sigma = std::sqrt(shot_noise * std::max(0.0, reading) * etalon_peak +
                               std::pow(read_noise * etalon_peak, 2));
      out.value(o, i) = reading + sigma * normal(rng);
    }
  }
  return out;
}

void write_eem_csv(const std::string& path, const ExcitationEmissionMatrix& m) {
  std::ofstream out(path);
  out << "# simulated fluorimeter\nem\\ex";
  for (double l : m.ex_nm) out << "," << l;
  out << "\n";
  out.precision(10);
  for (Eigen::Index o = 0; o < m.value.rows(); ++o) {
    out << m.em_nm[o];
    for (Eigen::Index i = 0; i < m.value.cols(); ++i) out << "," << m.value(o, i);
    out << "\n";
  }
}

}  // namespace kasha::test
