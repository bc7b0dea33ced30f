#include "material/glasses.h"

#include <cmath>

#include "core/csv_table.h"
#include "core/embedded_file.h"

namespace kasha {

double sellmeier_index(const std::vector<double>& B, const std::vector<double>& C_um2, double nm) {
  const double l2 = (nm / 1000) * (nm / 1000);
  double n2 = 1;
  for (size_t i = 0; i < B.size(); ++i) n2 += B[i] * l2 / (l2 - C_um2[i]);
  return n2 > 0 ? std::sqrt(n2) : NAN;
}

double cauchy_index(double A, double B_um2, double C_um4, double nm) {
  const double l2 = (nm / 1000) * (nm / 1000);
  return A + B_um2 / l2 + C_um4 / (l2 * l2);
}

namespace {
class IndexFormulaSpectrum : public Spectrum {
 public:
  explicit IndexFormulaSpectrum(std::function<double(double)> index) : index_(std::move(index)) {}
  SpectralSupport support() const override { return {false, true, 0, 0}; }

 protected:
  // 3-point Gauss–Legendre on pieces of at most 1 nm: the formulas are smooth on that scale.
  double raw_integral(double a, double b) const override {
    if (!(b > a)) return 0;
    const int pieces = static_cast<int>(std::ceil(b - a));
    const double h = (b - a) / pieces, x = std::sqrt(0.6) / 2;
    double sum = 0;
    for (int k = 0; k < pieces; ++k) {
      double m = a + (k + 0.5) * h;
      sum += h * (5 * index_(m - x * h) + 8 * index_(m) + 5 * index_(m + x * h)) / 18;
    }
    return sum;
  }
  double raw_value(double nm) const override { return index_(nm); }
  double raw_peak() const override { return index_(380); }

 private:
  std::function<double(double)> index_;
};
}  // namespace

SpectrumPtr index_spectrum(const std::function<double(double)>& index) {
  return std::make_shared<IndexFormulaSpectrum>(index);
}

namespace {
struct Glass {
  const char* name;
  std::vector<double> B, C_um2;
};
// Sellmeier coefficients as published: Schott's data sheets for N-BK7 and N-SF11; Malitson
// (1965) for fused silica; Daimon & Masumura (2007) for water at 20 °C (all as tabulated by
// refractiveindex.info). Their n_d (587.56 nm) is tested against the catalogues' 1.5168, 1.4585,
// 1.7847 and 1.3334.
const std::vector<Glass>& glasses() {
  static const std::vector<Glass> all = {
      {"BK7", {1.03961212, 0.231792344, 1.01046945}, {0.00600069867, 0.0200179144, 103.560653}},
      {"fused_silica",
       {0.6961663, 0.4079426, 0.8974794},
       {0.0684043 * 0.0684043, 0.1162414 * 0.1162414, 9.896161 * 9.896161}},
      {"SF11", {1.73759695, 0.313747346, 1.89878101}, {0.013188707, 0.0623068142, 155.23629}},
      {"water",
       {5.684027565e-1, 1.726177391e-1, 2.086189578e-2, 1.130748688e-1},
       {5.101829712e-3, 1.821153936e-2, 2.620722293e-2, 1.069792721e1}},
  };
  return all;
}

// pbrt-v4's other named glasses, as its tables give them (host/data/glass_NAME.csv).
const std::vector<std::string>& tabulated_glasses() {
  static const std::vector<std::string> names = {"BAF10", "FK51A", "LASF9", "SF5", "SF10"};
  return names;
}

// A tabulated index, linear between samples and its end values beyond them (an index of 0 is no
// glass).
SpectrumPtr glass_table(const std::string& name) {
  const std::string file = "glass_" + name + ".csv";
  const CsvTable table = parse_csv_table(embedded_data(file), file);
  std::vector<double> nm = {1.0}, n = {table.rows.front().at(1)};
  for (const auto& row : table.rows) {
    nm.push_back(row.at(0));
    n.push_back(row.at(1));
  }
  nm.push_back(1e5);
  n.push_back(n.back());
  return std::make_shared<PiecewiseLinearSpectrum>(nm, n);
}
}  // namespace

SpectrumPtr named_glass(const std::string& name) {
  for (const Glass& g : glasses())
    if (name == g.name)
      return index_spectrum([g](double nm) { return sellmeier_index(g.B, g.C_um2, nm); });
  for (const std::string& t : tabulated_glasses())
    if (name == t) return glass_table(t);
  return nullptr;
}

std::vector<std::string> named_glass_names() {
  std::vector<std::string> names;
  for (const Glass& g : glasses()) names.push_back(g.name);
  for (const std::string& t : tabulated_glasses()) names.push_back(t);
  return names;
}

}  // namespace kasha
