#include "color/cie_observer.h"

#include "core/csv_table.h"
#include "core/embedded_file.h"

namespace kasha {

std::string observer_name(Observer observer) {
  return observer == Observer::cie1964_10deg ? "CIE 1964 10°" : "CIE 1931 2°";
}

static std::array<SpectrumPtr, 3> load_cmf(const char* name) {
  CsvTable table = parse_csv_table(embedded_data(name), name);
  std::vector<double> nm, c[3];
  for (const auto& row : table.rows) {
    nm.push_back(row.at(0));
    for (int k = 0; k < 3; ++k) c[k].push_back(row.at(1 + k));
  }
  std::array<SpectrumPtr, 3> out;
  for (int k = 0; k < 3; ++k) out[k] = std::make_shared<PiecewiseLinearSpectrum>(nm, c[k]);
  return out;
}

const std::array<SpectrumPtr, 3>& cie_cmf(Observer observer) {
  static const std::array<SpectrumPtr, 3> two = load_cmf("CIE1931_2deg_xyz_cmf_360_830_1nm.csv");
  static const std::array<SpectrumPtr, 3> ten = load_cmf("CIE1964_10deg_xyz_cmf_360_830_1nm.csv");
  return observer == Observer::cie1964_10deg ? ten : two;
}

BinnedObserver::BinnedObserver(const WavelengthGrid& grid, Observer observer)
    : x(grid.resample(*cie_cmf(observer)[0])),
      y(grid.resample(*cie_cmf(observer)[1])),
      z(grid.resample(*cie_cmf(observer)[2])) {}

std::array<double, 3> BinnedObserver::xyz(const std::vector<double>& per_bin, double bin_nm) const {
  std::array<double, 3> out{0, 0, 0};
  for (size_t i = 0; i < per_bin.size(); ++i) {
    out[0] += x[i] * per_bin[i] * bin_nm;
    out[1] += y[i] * per_bin[i] * bin_nm;
    out[2] += z[i] * per_bin[i] * bin_nm;
  }
  return out;
}

}  // namespace kasha
