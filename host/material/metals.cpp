#include "material/metals.h"

#include "core/csv_table.h"
#include "core/embedded_file.h"

namespace kasha {

std::vector<std::string> builtin_metal_names() {
  // pbrt-v4's named metals (util/spectrum.cpp's tables, host/data/SOURCES.md).
  return {"Ag", "Al", "Au", "Cu", "CuZn", "MgO", "TiO2"};
}

MetalIndex builtin_metal(const std::string& name) {
  bool known = false;
  for (const std::string& n : builtin_metal_names()) known = known || n == name;
  if (!known) return {};
  const std::string file = "metal_" + name + ".csv";
  CsvTable table = parse_csv_table(embedded_data(file), file);
  // Beyond the table, its end values: a piecewise-linear spectrum is zero outside its samples, and
  // an index of 0 is no metal.
  std::vector<double> nm = {1.0}, n = {table.rows.front().at(1)}, k = {table.rows.front().at(2)};
  for (const auto& row : table.rows) {
    nm.push_back(row.at(0));
    n.push_back(row.at(1));
    k.push_back(row.at(2));
  }
  nm.push_back(1e5);
  n.push_back(n.back());
  k.push_back(k.back());
  return {std::make_shared<PiecewiseLinearSpectrum>(nm, n),
          std::make_shared<PiecewiseLinearSpectrum>(nm, k)};
}

}  // namespace kasha
