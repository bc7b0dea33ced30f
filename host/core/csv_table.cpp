#include "core/csv_table.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"
#include "core/printable.h"

namespace kasha {

static std::string trim(const std::string& s) {
  size_t a = s.find_first_not_of(" \t\r\n\"");
  size_t b = s.find_last_not_of(" \t\r\n\"");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

static std::vector<std::string> split_cells(const std::string& line) {
  char sep = ',';
  if (line.find(',') == std::string::npos) sep = line.find(';') != std::string::npos ? ';' : '\t';
  std::vector<std::string> cells;
  if (sep == '\t' && line.find('\t') == std::string::npos) {  // whitespace-separated columns
    std::istringstream words(line);
    for (std::string w; words >> w;) cells.push_back(trim(w));
    return cells;
  }
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, sep)) cells.push_back(trim(cell));
  if (!line.empty() && line.back() == sep) cells.push_back("");
  return cells;
}

static bool parse_number(const std::string& cell, double& out) {
  if (cell.empty()) return false;
  char* end = nullptr;
  out = std::strtod(cell.c_str(), &end);
  return end == cell.c_str() + cell.size();
}

// JASCO Spectra Manager text exports: "KEY<tab or comma>VALUE" header lines, then a line
// "XYDATA", then NPOINTS rows of data (the first holds the excitation wavelengths in a 3-D
// export), then an optional footer in any encoding.
static bool is_jasco_export(const std::string& text) {
  return text.rfind("TITLE", 0) == 0 && text.find("\nXYDATA") != std::string::npos;
}

CsvTable parse_csv_table(const std::string& text, const std::string& source) {
  CsvTable table;
  table.source = source;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  const bool jasco = is_jasco_export(text);
  bool in_data = !jasco;
  while (std::getline(in, line)) {
    ++line_no;
    std::string t = trim(line);
    if (!in_data) {
      if (t == "XYDATA") {
        in_data = true;
        table.jasco = true;
      } else {
        std::vector<std::string> cells = split_cells(t);
        if (cells.size() >= 2) table.fields[cells[0]] = cells[1];
      }
      continue;
    }
    if (jasco && !t.empty()) {
      // The data ends at the first row that is not all numbers (the footer).
      bool numeric = true;
      double v;
      std::vector<std::string> cells = split_cells(t);
      for (size_t c = 0; c < cells.size(); ++c)
        if (!parse_number(cells[c], v) && !(c == 0 && cells[c].empty())) numeric = false;
      if (!numeric) break;
      if (cells[0].empty() && table.rows.empty() && table.header.empty()) {
        table.header = cells;  // 3-D export: a blank corner cell, then the excitation wavelengths
        continue;
      }
    }
    if (t.empty() || t[0] == '#') continue;
    std::vector<std::string> cells = split_cells(t);
    double first;
    if (table.rows.empty() && table.header.empty() && !parse_number(cells[0], first)) {
      table.header = cells;
      continue;
    }
    std::vector<double> row(cells.size());
    for (size_t c = 0; c < cells.size(); ++c) {
      if (!parse_number(cells[c], row[c]))
        throw Error(printable(source) + ": line " + std::to_string(line_no) + ", column " +
                    std::to_string(c + 1) + ": not a number: \"" + printable(cells[c]) + "\"");
      if (!std::isfinite(row[c]))
        throw Error(printable(source) + ": line " + std::to_string(line_no) + ", column " +
                    std::to_string(c + 1) + ": value is not finite");
    }
    table.rows.push_back(std::move(row));
    table.row_lines.push_back(line_no);
  }
  return table;
}

CsvTable read_csv_table(const std::string& path) {
  return parse_csv_table(read_input_file(path, kMaxTextInputBytes), path);
}

void check_jasco_nanometers(const CsvTable& table) {
  if (!table.jasco) return;
  // A JASCO export names its x axis; kasha's tables are all in nm (a Raman or IR export in 1/CM
  // would otherwise be read as wavelengths).
  auto units = table.fields.find("XUNITS");
  if (units == table.fields.end())
    throw Error(printable(table.source) + ": JASCO export without XUNITS (expected NANOMETERS)");
  if (units->second != "NANOMETERS")
    throw Error(printable(table.source) + ": x units are " + printable(units->second) +
                ", not NANOMETERS");
}

}  // namespace kasha
