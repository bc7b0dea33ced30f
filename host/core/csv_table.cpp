#include "core/csv_table.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.h"

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

CsvTable parse_csv_table(const std::string& text, const std::string& source) {
  CsvTable table;
  table.source = source;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::string t = trim(line);
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
        throw Error(source + ": line " + std::to_string(line_no) + ", column " +
                    std::to_string(c + 1) + ": not a number: \"" + cells[c] + "\"");
      if (!std::isfinite(row[c]))
        throw Error(source + ": line " + std::to_string(line_no) + ", column " +
                    std::to_string(c + 1) + ": value is not finite");
    }
    table.rows.push_back(std::move(row));
    table.row_lines.push_back(line_no);
  }
  return table;
}

CsvTable read_csv_table(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_csv_table(text.str(), path);
}

}  // namespace kasha
