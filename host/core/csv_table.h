#pragma once
// Numeric tables in delimited text: comma, semicolon or tab separated, `#` comment lines, an
// optional header row. Every cell error names the file, line and column.
#include <string>
#include <vector>

namespace kasha {

struct CsvTable {
  std::string source;               // file name used in messages
  std::vector<std::string> header;  // empty when the first row is numeric
  std::vector<std::vector<double>> rows;
  std::vector<int> row_lines;  // 1-based line number of each row, for messages
};

// Parses `text` (named `source` in messages). A header is a first row whose first cell is not a
// number; every later cell must be a finite number.
CsvTable parse_csv_table(const std::string& text, const std::string& source);
CsvTable read_csv_table(const std::string& path);

}  // namespace kasha
