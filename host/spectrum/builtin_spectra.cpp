#include "spectrum/builtin_spectra.h"

#include <map>

#include "core/csv_table.h"
#include "core/embedded_file.h"

namespace kasha {

namespace {
const std::map<std::string, std::string>& table_files() {
  static const std::map<std::string, std::string> files = {
      {"A", "CIE_A.csv"},           {"D50", "CIE_D50.csv"},  {"D65", "CIE_D65.csv"},
      {"F1", "CIE_FL1.csv"},        {"F2", "CIE_FL2.csv"},   {"F3", "CIE_FL3.csv"},
      {"F4", "CIE_FL4.csv"},        {"F5", "CIE_FL5.csv"},   {"F6", "CIE_FL6.csv"},
      {"F7", "CIE_FL7.csv"},        {"F8", "CIE_FL8.csv"},   {"F9", "CIE_FL9.csv"},
      {"F10", "CIE_FL10.csv"},      {"F11", "CIE_FL11.csv"}, {"F12", "CIE_FL12.csv"},
      {"ACES_D60", "ACES_D60.csv"},
  };
  return files;
}
}  // namespace

SpectrumPtr builtin_spectrum(const std::string& name) {
  // Illuminant E: equal energy, 100 at every wavelength like the published relative tables.
  if (name == "E") return std::make_shared<ConstantSpectrum>(100.0);
  auto it = table_files().find(name);
  if (it == table_files().end()) return nullptr;
  CsvTable table = parse_csv_table(embedded_data(it->second), it->second);
  std::vector<double> nm, value;
  for (const auto& row : table.rows) {
    nm.push_back(row.at(0));
    value.push_back(row.at(1));
  }
  return std::make_shared<PiecewiseLinearSpectrum>(nm, value);
}

std::vector<std::string> builtin_spectrum_names() {
  std::vector<std::string> names = {"E"};
  for (const auto& [name, file] : table_files()) names.push_back(name);
  return names;
}

}  // namespace kasha
