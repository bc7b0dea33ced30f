#include "measure/fluorimeter.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/printable.h"
#include "measure/rank1_fit.h"

namespace kasha {

namespace {

std::string nm_text(double nm) {
  std::ostringstream o;
  o << nm << " nm";
  return o.str();
}

double positive_value(const Spectrum& s, double nm, const std::string& source,
                      const std::string& what) {
  double v = s.value(nm);
  if (!(v > 0))
    throw Error(printable(source) + ": " + what + " is " + (v == 0 ? "zero" : "negative") + " at " +
                nm_text(nm) + (v == 0 ? " (a table is zero outside its wavelengths)" : ""));
  return v;
}

}  // namespace

void check_band(const ExcitationEmissionMatrix& m, double band_nm,
                const std::string& estimated_from) {
  // A band as wide as the emission range leaves no reading outside it: the fit would see nothing
  // and the material's fluorescence would be all zero.
  const double span = m.em_nm.back() - m.em_nm.front();
  if (!(band_nm > 0 && band_nm < span)) {
    std::ostringstream msg;
    msg << (estimated_from.empty() ? "--band-nm " : printable(estimated_from) + ": band ±")
        << band_nm << " nm: the band must be narrower than the emission range of "
        << printable(m.source) << " (" << m.em_nm.front() << " to " << m.em_nm.back() << " nm)";
    throw Error(msg.str());
  }
}

std::vector<double> trapezoid_weights(const std::vector<double>& nm) {
  std::vector<double> w(nm.size(), 0.0);
  for (size_t k = 0; k + 1 < nm.size(); ++k) {
    double h = nm[k + 1] - nm[k];
    w[k] += 0.5 * h;
    w[k + 1] += 0.5 * h;
  }
  if (nm.size() == 1) w[0] = 1.0;
  return w;
}

double band_from_etalon(const ExcitationEmissionMatrix& etalon) {
  const auto& em = etalon.em_nm;
  std::vector<double> widths;
  for (size_t i = 0; i < etalon.ex_nm.size(); ++i) {
    double li = etalon.ex_nm[i];
    if (li < em.front() || li > em.back()) continue;
    // The diagonal peak: the largest reading within 50 nm of λi.
    Eigen::Index top = -1;
    for (size_t o = 0; o < em.size(); ++o)
      if (std::abs(em[o] - li) <= 50 && (top < 0 || etalon.value(o, i) > etalon.value(top, i)))
        top = o;
    if (top < 0 || etalon.value(top, i) <= 0) continue;
    double threshold = 0.02 * etalon.value(top, i), width = 0;
    Eigen::Index lo = top, hi = top;
    while (lo > 0 && etalon.value(lo, i) > threshold) --lo;
    while (hi + 1 < static_cast<Eigen::Index>(em.size()) && etalon.value(hi, i) > threshold) ++hi;
    width = std::max(li - em[lo], em[hi] - li);
    widths.push_back(width);
  }
  if (widths.empty())
    throw Error(
        etalon.source +
        ": missing band: no excitation wavelength has a diagonal peak inside the emission range");
  std::sort(widths.begin(), widths.end());
  double step = em.size() > 1 ? (em.back() - em.front()) / (em.size() - 1) : 0;
  // The 90th percentile ignores a column spoiled by noise.
  return widths[static_cast<size_t>(0.9 * (widths.size() - 1))] + step;
}

// The grids of the sample's and the etalon's matrices must be one.
static void check_same_grid(const ExcitationEmissionMatrix& S, const ExcitationEmissionMatrix& E) {
  if (S.same_grid(E)) return;
  {
    std::ostringstream msg;
    msg << "grids do not match: " << S.source << " has " << S.ex_nm.size() << " excitation x "
        << S.em_nm.size() << " emission wavelengths (" << S.ex_nm.front() << "–" << S.ex_nm.back()
        << " / " << S.em_nm.front() << "–" << S.em_nm.back() << " nm), " << E.source << " has "
        << E.ex_nm.size() << " x " << E.em_nm.size() << " (" << E.ex_nm.front() << "–"
        << E.ex_nm.back() << " / " << E.em_nm.front() << "–" << E.em_nm.back() << " nm)";
    throw Error(msg.str());
  }
}

// Per excitation wavelength: the band's sums of the etalon (R̄_e) and the sample (R̄), the
// etalon's reflectance over π (f_e) and the detector's sensitivity (C(λi)), where a band exists.
struct BandSums {
  std::vector<double> rbar_e, rbar, f_e, c_i;
  std::vector<bool> has_band;
};

static BandSums band_sums(const FluorimeterInput& in, const Eigen::MatrixXd& band,
                          const std::vector<double>& w, double eps) {
  const ExcitationEmissionMatrix &S = in.sample, &E = in.etalon;
  const Eigen::Index n_o = S.em_nm.size(), n_i = S.ex_nm.size();
  BandSums r{std::vector<double>(n_i, 0.0), std::vector<double>(n_i, 0.0),
             std::vector<double>(n_i, 0.0), std::vector<double>(n_i, 1.0),
             std::vector<bool>(n_i, false)};
  for (Eigen::Index i = 0; i < n_i; ++i) {
    double li = S.ex_nm[i];
    for (Eigen::Index o = 0; o < n_o; ++o)
      if (band(o, i) > 0) {
        r.rbar_e[i] += E.value(o, i) * w[o];
        r.rbar[i] += S.value(o, i) * w[o];
        r.has_band[i] = true;
      }
    bool inside = li >= S.em_nm.front() && li <= S.em_nm.back();
    if (inside && !r.has_band[i])
      throw Error(printable(S.source) + ": empty band: no emission sample lies within ±" +
                  std::to_string(eps) + " nm of the excitation at " + nm_text(li) +
                  " (--band-nm is narrower than the emission grid's step)");
    if (!r.has_band[i]) continue;
    if (!(r.rbar_e[i] > 0))
      throw Error(printable(E.source) + ": the etalon reading is zero in the band at excitation " +
                  nm_text(li));
    r.f_e[i] = positive_value(*in.etalon_reflectance, li, in.etalon_reflectance_source,
                              "etalon reflectance") /
               M_PI;
    if (in.sensitivity)
      r.c_i[i] = positive_value(*in.sensitivity, li, in.sensitivity_source, "detector sensitivity");
  }
  if (std::count(r.has_band.begin(), r.has_band.end(), true) < 2)
    throw Error(printable(S.source) +
                ": fewer than two excitation wavelengths lie inside the emission range (" +
                nm_text(S.em_nm.front()) + " to " + nm_text(S.em_nm.back()) +
                "); the material's spectra need two");
  return r;
}

MeasuredMaterial material_from_fluorimeter(const FluorimeterInput& in) {
  const ExcitationEmissionMatrix &S = in.sample, &E = in.etalon;
  check_same_grid(S, E);
  MeasuredMaterial m = measured_from(S, "fluorimeter");
  const Eigen::Index n_o = S.em_nm.size(), n_i = S.ex_nm.size();
  m.band_estimated = in.band_nm <= 0;
  m.band_nm = m.band_estimated ? band_from_etalon(E) : in.band_nm;
  const double eps = m.band_nm;
  check_band(S, eps, m.band_estimated ? E.source : "");
  const std::vector<double> w = trapezoid_weights(S.em_nm);

  // Masks: the band around the diagonal and the grating's second order near λo = 2λi.
  Eigen::MatrixXd band = Eigen::MatrixXd::Zero(n_o, n_i);
  m.known = Eigen::MatrixXd::Ones(n_o, n_i);
  for (Eigen::Index i = 0; i < n_i; ++i)
    for (Eigen::Index o = 0; o < n_o; ++o) {
      double lo = S.em_nm[o], li = S.ex_nm[i];
      if (std::abs(lo - li) <= eps) band(o, i) = 1, m.known(o, i) = 0;
      if (std::abs(lo - 2 * li) <= eps) m.known(o, i) = 0, ++m.second_order_masked;
    }

  // Per excitation wavelength: R̄_e, f_e and the sensitivity at λi.
  const BandSums sums = band_sums(in, band, w, eps);
  const std::vector<double>&rbar_e = sums.rbar_e, &rbar = sums.rbar, &f_e = sums.f_e,
        &c_i = sums.c_i;
  const std::vector<bool>& has_band = sums.has_band;
  std::vector<double> c_o(n_o, 1.0);
  if (in.sensitivity)
    for (Eigen::Index o = 0; o < n_o; ++o)
      c_o[o] = positive_value(*in.sensitivity, S.em_nm[o], in.sensitivity_source,
                              "detector sensitivity");

  // Corrected eq. 8 on every entry; only the known ones enter the fit. Columns without a band
  // (excitation outside the emission range) have no R̄_e to scale by and stay out.
  m.fluorescence = Eigen::MatrixXd::Zero(n_o, n_i);
  for (Eigen::Index i = 0; i < n_i; ++i) {
    if (!has_band[i]) {
      m.known.col(i).setZero();
      continue;
    }
    for (Eigen::Index o = 0; o < n_o; ++o)
      m.fluorescence(o, i) = f_e[i] * S.value(o, i) / rbar_e[i] * c_i[i] / c_o[o];
  }
  bool any_known = m.known.sum() > 0;
  if (!any_known)
    throw Error(printable(S.source) + ": no off-band entries left to fit the fluorescence to");
  Rank1Fit fit = fit_rank1_nonnegative(m.fluorescence, m.known);
  m.fit = fit.e * fit.a.transpose();
  m.rank1_residual = fit.relative_residual;
  m.rank1_signal_residual = fit.signal_residual;

  // Normalize: e(λo) = e'/∫e', a(λi) = π a' ∫e'.
  double e_integral = 0;
  for (Eigen::Index o = 0; o < n_o; ++o) e_integral += fit.e[o] * w[o];
  for (Eigen::Index o = 0; o < n_o; ++o) {
    m.emission.nm.push_back(S.em_nm[o]);
    m.emission.value.push_back(e_integral > 0 ? fit.e[o] / e_integral : 0.0);
  }

  for (Eigen::Index i = 0; i < n_i; ++i) {
    if (!has_band[i]) continue;
    m.excitation.nm.push_back(S.ex_nm[i]);
    m.excitation.value.push_back(M_PI * fit.a[i] * e_integral);
    // Corrected eq. 7: subtract the fluorescence the fit puts inside the band, in reading units.
    double fluorescence_in_band = 0;
    for (Eigen::Index o = 0; o < n_o; ++o)
      if (band(o, i) > 0)
        fluorescence_in_band += m.fit(o, i) * rbar_e[i] / f_e[i] * c_o[o] / c_i[i] * w[o];
    double rho = M_PI * f_e[i] * (rbar[i] - fluorescence_in_band) / rbar_e[i];
    if (rho < 0) {
      m.notes.push_back("passive reflectance " + std::to_string(rho) + " at " +
                        nm_text(S.ex_nm[i]) + " (noise) set to 0");
      rho = 0;
    }
    m.passive.nm.push_back(S.ex_nm[i]);
    m.passive.value.push_back(rho);
  }
  // Outside the emission range the etalon's reflection is not seen, so the lamp at λi is unknown
  // and neither ρ nor a can be scaled there: those columns are left out and reported.
  for (Eigen::Index i = 0; i < n_i; ++i)
    if (!has_band[i])
      m.notes.push_back("no passive reflectance or excitation at " + nm_text(S.ex_nm[i]) +
                        ": outside the emission range");
  drop_zero_fluorescence(m);
  return m;
}

}  // namespace kasha
