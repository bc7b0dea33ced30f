#include "spectrum/spectrum.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace kasha {

SpectralSupport ConstantSpectrum::support() const {
  SpectralSupport s;
  s.empty = value_ == 0.0;
  s.unbounded = !s.empty;
  return s;
}

PiecewiseLinearSpectrum::PiecewiseLinearSpectrum(std::vector<double> nm, std::vector<double> value)
    : nm_(std::move(nm)), value_(std::move(value)) {}

SpectralSupport PiecewiseLinearSpectrum::support() const {
  SpectralSupport s;
  size_t first = 0, last = value_.size();
  while (first < value_.size() && value_[first] == 0.0) ++first;
  if (first == value_.size()) {
    s.empty = true;
    return s;
  }
  while (last > 0 && value_[last - 1] == 0.0) --last;
  s.lo_nm = nm_[first > 0 ? first - 1 : 0];
  s.hi_nm = nm_[last < nm_.size() ? last : nm_.size() - 1];
  return s;
}

double PiecewiseLinearSpectrum::raw_value(double x) const {
  if (x < nm_.front() || x > nm_.back()) return 0.0;
  size_t k = std::upper_bound(nm_.begin(), nm_.end(), x) - nm_.begin();
  if (k == 0) return value_.front();
  if (k == nm_.size()) return value_.back();
  double t = (x - nm_[k - 1]) / (nm_[k] - nm_[k - 1]);
  return value_[k - 1] + t * (value_[k] - value_[k - 1]);
}

double PiecewiseLinearSpectrum::raw_peak() const {
  return *std::max_element(value_.begin(), value_.end());
}

double PiecewiseLinearSpectrum::raw_integral(double a, double b) const {
  a = std::max(a, nm_.front());
  b = std::min(b, nm_.back());
  if (!(a < b)) return 0.0;
  // Exact for a piecewise-linear function: the trapezoid rule on each piece inside [a, b].
  size_t k = std::upper_bound(nm_.begin(), nm_.end(), a) - nm_.begin();
  if (k == 0) k = 1;
  double sum = 0.0;
  for (; k < nm_.size() && nm_[k - 1] < b; ++k) {
    double l = std::max(a, nm_[k - 1]), r = std::min(b, nm_[k]);
    if (r > l) sum += 0.5 * (r - l) * (raw_value(l) + raw_value(r));
  }
  return sum;
}

GaussianSpectrum::GaussianSpectrum(double center_nm, double fwhm_nm)
    : center_(center_nm), sigma_(fwhm_nm / (2.0 * std::sqrt(2.0 * std::log(2.0)))) {}

SpectralSupport GaussianSpectrum::support() const {
  // Where the value exceeds 1e-4 of the peak.
  double half = sigma_ * std::sqrt(2.0 * std::log(1e4));
  return {false, false, center_ - half, center_ + half};
}

double GaussianSpectrum::raw_value(double nm) const {
  double z = (nm - center_) / sigma_;
  return std::exp(-0.5 * z * z);
}

double LineSpectrum::raw_value(double) const {
  throw Error(
      "a line spectrum has no value at a single wavelength; use a tabulated or smooth spectrum");
}

double GaussianSpectrum::raw_integral(double a, double b) const {
  double k = 1.0 / (sigma_ * std::sqrt(2.0));
  return sigma_ * std::sqrt(M_PI / 2.0) *
         (std::erf((b - center_) * k) - std::erf((a - center_) * k));
}

namespace {
constexpr double kPlanck = 6.62607015e-34;
constexpr double kLightSpeed = 299792458.0;
constexpr double kBoltzmann = 1.380649e-23;
}  // namespace

double BlackbodySpectrum::raw_value(double nm) const {
  if (nm <= 0) return 0.0;
  double l = nm * 1e-9;
  double x = kPlanck * kLightSpeed / (l * kBoltzmann * kelvin_);
  // Per metre of wavelength, then per nanometre.
  return 2.0 * kPlanck * kLightSpeed * kLightSpeed / std::pow(l, 5) / std::expm1(x) * 1e-9;
}

double BlackbodySpectrum::raw_peak() const {
  return raw_value(2.897771955e6 / kelvin_);  // Wien's displacement law
}

SpectralSupport BlackbodySpectrum::support() const {
  // Non-negligible (> 1e-4 of the peak, Wien's law) from some short wavelength up.
  double peak_nm = 2.897771955e6 / kelvin_;
  double peak = raw_value(peak_nm);
  double lo = peak_nm;
  while (lo > 1.0 && raw_value(lo) > 1e-4 * peak) lo *= 0.99;
  return {false, false, lo, 1e9};
}

double BlackbodySpectrum::raw_integral(double a, double b) const {
  // Planck's law is smooth on a bin's scale: 8-point Gauss–Legendre on 1 nm pieces is exact to
  // double rounding for any bin, which is what "exact bin averaging" asks of it.
  static const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                              0.9602898564975363};
  static const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                              0.1012285362903763};
  if (!(a < b)) return 0.0;
  int pieces = std::max(1, static_cast<int>(std::ceil(b - a)));
  double h = (b - a) / pieces, sum = 0.0;
  for (int p = 0; p < pieces; ++p) {
    double mid = a + (p + 0.5) * h, half = 0.5 * h;
    for (int i = 0; i < 4; ++i)
      sum += w[i] * half * (raw_value(mid - half * x[i]) + raw_value(mid + half * x[i]));
  }
  return sum;
}

}  // namespace kasha
