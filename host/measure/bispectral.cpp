#include "measure/bispectral.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/printable.h"
#include "measure/fluorimeter.h"
#include "measure/rank1_fit.h"

namespace kasha {

MeasuredMaterial material_from_bispectral(const ExcitationEmissionMatrix& D, double band_nm) {
  MeasuredMaterial m = measured_from(D, "bispectral");
  m.fluorescence = D.value;
  const Eigen::Index n_o = D.em_nm.size(), n_i = D.ex_nm.size();
  // The diagonal is where λo = λi; those entries hold reflection and fluorescence together. The
  // band-pass of the instrument's monochromators spreads reflection into the neighbouring bins,
  // so by default the band also masks one bin on each side from the fit.
  const double step = n_o > 1 ? (D.em_nm.back() - D.em_nm.front()) / (n_o - 1) : 1.0;
  m.band_nm = band_nm > 0 ? band_nm : step;
  m.band_estimated = band_nm <= 0;
  check_band(D, m.band_nm, m.band_estimated ? D.source : "");
  std::vector<Eigen::Index> diagonal(n_i, -1);
  m.known = Eigen::MatrixXd::Ones(n_o, n_i);
  for (Eigen::Index i = 0; i < n_i; ++i)
    for (Eigen::Index o = 0; o < n_o; ++o) {
      double d = std::abs(D.em_nm[o] - D.ex_nm[i]);
      if (d < 1e-6) diagonal[i] = o;
      if (d <= m.band_nm + 1e-6) m.known(o, i) = 0;
    }
  const auto on_diagonal =
      std::count_if(diagonal.begin(), diagonal.end(), [](Eigen::Index d) { return d >= 0; });
  if (on_diagonal == 0)
    throw Error(
        printable(D.source) +
        ": missing band: no excitation wavelength equals an emission wavelength (no diagonal)");
  // The passive reflectance is tabulated on the diagonal and needs two samples.
  if (on_diagonal < 2)
    throw Error(printable(D.source) +
                ": only one excitation wavelength equals an emission wavelength; the passive "
                "reflectance needs two");

  Rank1Fit fit = fit_rank1_nonnegative(m.fluorescence, m.known);
  m.fit = fit.e * fit.a.transpose();
  m.rank1_residual = fit.relative_residual;
  m.rank1_signal_residual = fit.signal_residual;

  const double e_sum = fit.e.sum();  // per-bin values: ê = e'/Σe', a = a' Σe'
  for (Eigen::Index o = 0; o < n_o; ++o) {
    m.emission.nm.push_back(D.em_nm[o]);
    m.emission.value.push_back(e_sum > 0 ? fit.e[o] / e_sum / step : 0.0);
  }
  for (Eigen::Index i = 0; i < n_i; ++i) {
    m.excitation.nm.push_back(D.ex_nm[i]);
    m.excitation.value.push_back(fit.a[i] * e_sum);
    if (diagonal[i] < 0) continue;
    double rho = D.value(diagonal[i], i) - m.fit(diagonal[i], i);
    if (rho < 0) {
      std::ostringstream note;
      note << "passive reflectance " << rho << " at " << D.ex_nm[i] << " nm (noise) set to 0";
      m.notes.push_back(note.str());
      rho = 0;
    }
    m.passive.nm.push_back(D.ex_nm[i]);
    m.passive.value.push_back(rho);
  }
  drop_zero_fluorescence(m);
  return m;
}

}  // namespace kasha
