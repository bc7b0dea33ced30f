#include "measure/eem.h"

#include <algorithm>
#include <cmath>

#include "core/csv_table.h"
#include "core/error.h"
#include "core/printable.h"

namespace kasha {

bool ExcitationEmissionMatrix::same_grid(const ExcitationEmissionMatrix& o) const {
  auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
      if (std::abs(a[i] - b[i]) > 1e-6 * std::max(1.0, std::abs(a[i]))) return false;
    return true;
  };
  return same(ex_nm, o.ex_nm) && same(em_nm, o.em_nm);
}

static void check_increasing(const std::vector<double>& nm, const std::string& what,
                             const std::string& path) {
  for (size_t i = 0; i < nm.size(); ++i) {
    if (!(nm[i] > 0))
      throw Error(printable(path) + ": " + what + " wavelength " + std::to_string(nm[i]) +
                  " is not positive");
    if (i > 0 && nm[i] <= nm[i - 1])
      throw Error(printable(path) + ": " + what + " wavelengths must increase");
  }
}

ExcitationEmissionMatrix read_eem(const std::string& path) {
  CsvTable t = read_csv_table(path);
  check_jasco_nanometers(t);
  ExcitationEmissionMatrix m;
  m.source = path;
  size_t first_row = 0;
  if (!t.header.empty()) {
    // Our layout: a label cell, then λi as text that must parse as numbers.
    for (size_t c = 1; c < t.header.size(); ++c) {
      char* end = nullptr;
      double v = std::strtod(t.header[c].c_str(), &end);
      if (t.header[c].empty() || *end != '\0' || !std::isfinite(v))
        throw Error(printable(path) + ": header row, column " + std::to_string(c + 1) +
                    ": excitation wavelength \"" + printable(t.header[c]) + "\" is not a number");
      m.ex_nm.push_back(v);
    }
  } else if (!t.rows.empty()) {
    // A JASCO 3-D export without a corner cell: the first row is all excitation wavelengths.
    m.ex_nm = t.rows[0];
    if (t.rows.size() > 1 && t.rows[1].size() == t.rows[0].size()) m.ex_nm.erase(m.ex_nm.begin());
    first_row = 1;
  }
  if (m.ex_nm.empty()) throw Error(path + ": no excitation wavelengths in the first row");
  if (t.rows.size() <= first_row) throw Error(path + ": no emission rows");
  const size_t rows = t.rows.size() - first_row, cols = m.ex_nm.size();
  m.value.resize(rows, cols);
  for (size_t r = 0; r < rows; ++r) {
    const std::vector<double>& row = t.rows[first_row + r];
    if (row.size() != cols + 1)
      throw Error(path + ": line " + std::to_string(t.row_lines[first_row + r]) + ": " +
                  std::to_string(row.size()) + " cells, expected " + std::to_string(cols + 1) +
                  " (emission wavelength and one reading per excitation wavelength)");
    m.em_nm.push_back(row[0]);
    for (size_t c = 0; c < cols; ++c) m.value(r, c) = row[c + 1];
  }
  if (t.jasco && m.em_nm.size() > 1 && m.em_nm.front() > m.em_nm.back()) {
    std::reverse(m.em_nm.begin(), m.em_nm.end());
    m.value = m.value.colwise().reverse().eval();
  }
  check_increasing(m.ex_nm, "excitation", path);
  check_increasing(m.em_nm, "emission", path);
  // A material's spectra are tabulated on these wavelengths and need two samples each; and a
  // matrix with nothing above zero is no measurement (a material from it would be refused).
  if (m.ex_nm.size() < 2)
    throw Error(printable(path) +
                ": only one excitation wavelength (column); a matrix needs two "
                "or more");
  if (m.em_nm.size() < 2)
    throw Error(printable(path) +
                ": only one emission wavelength (row); a matrix needs two or "
                "more");
  if (!(m.value.maxCoeff() > 0))
    throw Error(printable(path) + ": no reading is above zero (all " +
                (m.value.minCoeff() == 0 ? "zero" : "zero or negative") + "): not a measurement");
  return m;
}

}  // namespace kasha
