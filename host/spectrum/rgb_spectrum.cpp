#include "spectrum/rgb_spectrum.h"

#include <algorithm>
#include <cmath>

#include "core/csv_table.h"
#include "core/embedded_file.h"

namespace kasha {

const float* rgb_table_data(std::size_t* floats);  // spectrum/rgb_table_data.cpp

namespace {

struct RgbTable {
  const float* data = nullptr;
  int res = kRgbTableRes;
  std::vector<double> scale;  // the z axis

  RgbTable() {
    size_t n;
    data = rgb_table_data(&n);
    if (n != size_t(3) * res * res * res * 3) std::abort();  // a build error, not user input
    for (int k = 0; k < res; ++k) scale.push_back(rgb_table_scale(k, res));
  }

  SigmoidCoefficients lookup(std::array<double, 3> rgb) const {
    for (double& v : rgb) v = std::clamp(v, 0.0, 1.0);
    if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) {
      // Grey: the constant S(c2) = v.
      double v = rgb[0];
      if (v <= 0) return {0, 0, -INFINITY};
      if (v >= 1) return {0, 0, INFINITY};
      return {0, 0, (v - 0.5) / std::sqrt(v * (1 - v))};
    }
    const int l = int(std::max_element(rgb.begin(), rgb.end()) - rgb.begin());
    const double z = rgb[l], x = rgb_table_ratio_index(rgb[(l + 1) % 3] / z, res),
                 y = rgb_table_ratio_index(rgb[(l + 2) % 3] / z, res);
    int zi = int(std::upper_bound(scale.begin(), scale.end(), z) - scale.begin()) - 1;
    zi = std::clamp(zi, 0, res - 2);
    const int xi = std::min(int(x), res - 2), yi = std::min(int(y), res - 2);
    const double dz = (z - scale[zi]) / (scale[zi + 1] - scale[zi]), dx = x - xi, dy = y - yi;
    SigmoidCoefficients c{0, 0, 0};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int e = 0; e < 2; ++e) {
          double w = (a ? dz : 1 - dz) * (b ? dy : 1 - dy) * (e ? dx : 1 - dx);
          size_t at = ((size_t(l) * res + zi + a) * res + yi + b) * res + xi + e;
          for (int q = 0; q < 3; ++q) c[q] += w * data[3 * at + q];
        }
    return c;
  }
};

const RgbTable& table() {
  static const RgbTable t;
  return t;
}

// D65 (host/data/CIE_D65.csv) scaled to luminance 1 against the CIE 1931 ȳ.
struct NormalizedD65 {
  std::vector<double> nm, value;
  NormalizedD65() {
    const CsvTable d65 = parse_csv_table(embedded_data("CIE_D65.csv"), "CIE_D65.csv");
    const char* cmf_file = "CIE1931_2deg_xyz_cmf_360_830_1nm.csv";
    const CsvTable cmf = parse_csv_table(embedded_data(cmf_file), cmf_file);
    for (const auto& row : d65.rows) {
      nm.push_back(row[0]);
      value.push_back(row[1]);
    }
    double num = 0, den = 0;
    for (const auto& row : cmf.rows) {
      num += row[2] * at(row[0]);
      den += row[2];
    }
    for (double& v : value) v *= den / num;
  }
  double at(double l) const {
    if (l < nm.front() || l > nm.back()) return 0;
    size_t k = std::upper_bound(nm.begin(), nm.end(), l) - nm.begin();
    if (k >= nm.size()) return value.back();
    return value[k - 1] + (l - nm[k - 1]) / (nm[k] - nm[k - 1]) * (value[k] - value[k - 1]);
  }
};

// ∫_a^b f by Simpson's rule on steps of at most 1 nm: the functions here are smooth.
template <class F>
double integrate(F f, double a, double b) {
  if (!(b > a)) return 0;
  int n = std::max(2, 2 * int(std::ceil((b - a) / 2)));
  double h = (b - a) / n, s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * f(a + i * h);
  return s * h / 3;
}

}  // namespace

SigmoidCoefficients rgb_sigmoid(const std::array<double, 3>& rgb) {
  return table().lookup(rgb);
}

SigmoidCoefficients rgb_unbounded_sigmoid(const std::array<double, 3>& rgb, double* scale) {
  const double m = std::max({rgb[0], rgb[1], rgb[2], 0.0});
  *scale = 2 * m;
  if (m <= 0) return {0, 0, -INFINITY};
  return table().lookup({rgb[0] / *scale, rgb[1] / *scale, rgb[2] / *scale});
}

double d65_normalized(double nm) {
  static const NormalizedD65 d;
  return d.at(nm);
}

SpectrumPtr d65_luminance_one() {
  std::vector<double> nm, v;
  for (int l = 300; l <= 780; l += 5) {
    nm.push_back(l);
    v.push_back(d65_normalized(l));
  }
  return std::make_shared<PiecewiseLinearSpectrum>(nm, v);
}

double RgbReflectanceSpectrum::raw_integral(double a, double b) const {
  return integrate([this](double l) { return sigmoid_spectrum(c_, l); }, a, b);
}

RgbIlluminantSpectrum::RgbIlluminantSpectrum(const std::array<double, 3>& rgb) {
  c_ = rgb_unbounded_sigmoid(rgb, &scale_);
}

double RgbIlluminantSpectrum::raw_value(double nm) const {
  return scale_ * sigmoid_spectrum(c_, nm) * d65_normalized(nm);
}

double RgbIlluminantSpectrum::raw_integral(double a, double b) const {
  // D65's table has kinks every 5 nm: integrate piece by piece between them.
  double sum = 0;
  for (double lo = std::max(a, 300.0); lo < std::min(b, 780.0);) {
    double hi = std::min({b, 780.0, 5 * std::floor(lo / 5) + 5});
    sum += integrate([this](double l) { return raw_value(l); }, lo, hi);
    lo = hi;
  }
  return sum;
}

double RgbIlluminantSpectrum::raw_peak() const {
  double p = 0;
  for (double l = 300; l <= 780; l += 1) p = std::max(p, raw_value(l));
  return p;
}

}  // namespace kasha
