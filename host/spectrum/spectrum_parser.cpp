#include "spectrum/spectrum_parser.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/csv_table.h"
#include "core/error.h"
#include "core/printable.h"
#include "spectrum/builtin_spectra.h"
#include "spectrum/rgb_spectrum.h"

namespace kasha {

std::string spectrum_value_beyond(double value) {
  std::ostringstream msg;
  msg << "a spectrum value of " << value << " is beyond 1e30";
  return msg.str();
}

SpectrumPtr make_tabulated_spectrum(const std::vector<double>& nm, const std::vector<double>& value,
                                    const std::string& where, const std::vector<int>& lines) {
  if (nm.size() != value.size())
    throw Error(where + ": " + std::to_string(nm.size()) + " wavelengths but " +
                std::to_string(value.size()) + " values");
  if (nm.size() < 2) throw Error(where + ": a tabulated spectrum needs at least two samples");
  for (size_t i = 0; i < nm.size(); ++i) {
    std::ostringstream at;
    at << where << ": ";
    if (i < lines.size()) at << "line " << lines[i] << ": ";
    at << "at " << nm[i] << " nm: ";
    if (!std::isfinite(nm[i]) || !std::isfinite(value[i]))
      throw Error(at.str() + "value is not finite");
    if (nm[i] <= 0) throw Error(at.str() + "wavelength must be positive");
    if (value[i] < 0) {
      std::ostringstream v;
      v << value[i];
      throw Error(at.str() + "negative value " + v.str());
    }
    if (value[i] > kMaxSpectrumValue) throw Error(at.str() + spectrum_value_beyond(value[i]));
    if (i > 0 && nm[i] <= nm[i - 1]) throw Error(at.str() + "wavelengths must increase");
  }
  return std::make_shared<PiecewiseLinearSpectrum>(nm, value);
}

SpectrumPtr read_spectrum_csv(const std::string& path, const std::string& column) {
  CsvTable table = read_csv_table(path);
  check_jasco_nanometers(table);
  if (table.rows.empty()) throw Error(printable(path) + ": no data rows");
  size_t col = 1;
  if (!column.empty()) {
    col = 0;
    for (size_t c = 1; c < table.header.size(); ++c)
      if (table.header[c] == column) col = c;
    if (col == 0)
      throw Error(printable(path) + ": no column named \"" + printable(column) +
                  "\" in the header");
  } else if (table.rows[0].size() != 2) {
    throw Error(path + ": expected two columns (nm, value), found " +
                std::to_string(table.rows[0].size()) + "; choose one with \"column\"");
  }
  std::vector<double> nm, value;
  std::vector<int> lines;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    if (table.rows[r].size() <= col)
      throw Error(path + ": line " + std::to_string(table.row_lines[r]) + ": missing column " +
                  std::to_string(col + 1));
    nm.push_back(table.rows[r][0]);
    value.push_back(table.rows[r][col]);
    lines.push_back(table.row_lines[r]);
  }
  // JASCO instruments export from the long wavelength down.
  if (table.jasco && nm.size() > 1 && nm.front() > nm.back()) {
    std::reverse(nm.begin(), nm.end());
    std::reverse(value.begin(), value.end());
    std::reverse(lines.begin(), lines.end());
  }
  return make_tabulated_spectrum(nm, value, path, lines);
}

// Three linear RGB components in [0, hi].
static std::array<double, 3> rgb_triple(const JsonNode& node, double hi) {
  std::vector<double> v = node.numbers();
  if (v.size() != 3) node.fail("expected three numbers (linear sRGB)");
  for (double x : v)
    if (!(x >= 0 && x <= hi)) {
      std::ostringstream msg;
      msg << "an RGB component of " << x << " is outside [0, " << hi << "]";
      node.fail(msg.str());
    }
  return {v[0], v[1], v[2]};
}

SpectrumPtr parse_spectrum(const JsonNode& node) {
  if (node.is_number()) {
    double v = node.number();
    if (v < 0) node.fail("negative spectrum value");
    if (v > kMaxSpectrumValue) node.fail(spectrum_value_beyond(v));
    return std::make_shared<ConstantSpectrum>(v);
  }
  if (node.is_string()) {
    std::string name = node.string();
    if (SpectrumPtr s = builtin_spectrum(name)) return s;
    std::string known;
    for (const auto& n : builtin_spectrum_names()) known += (known.empty() ? "" : ", ") + n;
    node.fail("unknown built-in spectrum \"" + name + "\" (known: " + known + ")");
  }
  if (!node.is_object()) node.fail("expected a spectrum: a number, a built-in name or an object");

  SpectrumPtr s;
  std::string where = node.where();
  if (auto csv = node.find("csv")) {
    // An empty name would resolve to the scene's own folder: file_path refuses it.
    const std::filesystem::path file = csv->file_path();
    std::string column;
    if (auto c = node.find("column")) column = c->string();
    s = read_spectrum_csv(file.string(), column);
  } else if (auto nm = node.find("nm")) {
    s = make_tabulated_spectrum(nm->numbers(), node.at("value").numbers(), where);
  } else if (auto kelvin = node.find("blackbody_K")) {
    s = std::make_shared<BlackbodySpectrum>(kelvin->number_in(1.0, 1e6));
  } else if (auto center = node.find("gaussian_nm")) {
    double c = center->number_in(1.0, 1e5);
    s = std::make_shared<GaussianSpectrum>(c, node.at("fwhm_nm").number_in(1e-6, 1e5));
  } else if (auto line = node.find("line_nm")) {
    s = std::make_shared<LineSpectrum>(line->number_in(1.0, 1e5));
  } else if (auto rgb = node.find("rgb")) {
    // A reflectance's colour, linear sRGB in [0, 1] (spectrum/rgb_spectrum.h).
    s = std::make_shared<RgbReflectanceSpectrum>(rgb_triple(*rgb, 1.0));
  } else if (auto rgb = node.find("rgb_illuminant")) {
    s = std::make_shared<RgbIlluminantSpectrum>(rgb_triple(*rgb, kMaxSpectrumValue));
  } else {
    node.fail(
        "expected one of \"csv\", \"nm\"/\"value\", \"blackbody_K\", \"gaussian_nm\"/\"fwhm_nm\", "
        "\"line_nm\", \"rgb\", \"rgb_illuminant\"");
  }
  auto scale = node.find("scale");
  if (scale) {
    double k = scale->number();
    if (k < 0) scale->fail("scale must not be negative");
    s->set_scale(k);
  }
  // A scale can carry any form past the limit (a blackbody's peak only gets there scaled).
  if (!(s->peak() <= kMaxSpectrumValue))
    (scale ? *scale : node).fail(spectrum_value_beyond(s->peak()));
  node.finish();
  return s;
}

}  // namespace kasha
