#pragma once
// Numeric tables in delimited text: comma, semicolon, tab or space separated, `#` comment lines, an
// optional header row; also JASCO Spectra Manager exports (header fields, XYDATA, footer). Every
// cell error names the file, line and column.
#include <map>
#include <string>
#include <vector>

namespace kasha {

struct CsvTable {
  std::string source;               // file name used in messages
  std::vector<std::string> header;  // empty when the first row is numeric
  std::vector<std::vector<double>> rows;
  std::vector<int> row_lines;                 // 1-based line number of each row, for messages
  bool jasco = false;                         // read from a JASCO Spectra Manager export
  std::map<std::string, std::string> fields;  // its header fields (XUNITS, NPOINTS, ...)
};

// Parses `text` (named `source` in messages). A header is a first row whose first cell is not a
// number; every later cell must be a finite number.
CsvTable parse_csv_table(const std::string& text, const std::string& source);
// Reads `path` through read_input_file (regular files, at most kMaxTextInputBytes).
CsvTable read_csv_table(const std::string& path);
// A JASCO export's x axis must be in NANOMETERS (every route that reads wavelengths checks it);
// other tables pass.
void check_jasco_nanometers(const CsvTable& table);

}  // namespace kasha
