#include "study/convergence_log.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv_table.h"
#include "core/error.h"
#include "study/image_error.h"

namespace kasha {

void ConvergenceLog::pass_done(const PassRecord& record, const Film& film) {
  LogRow row;
  row.integrator = record.integrator;
  row.pass = record.pass;
  row.seconds = record.seconds;
  row.camera_paths = record.camera_paths;
  row.photons = record.photons;
  if (reference_) {
    ImageError e = image_error(film.image(), *reference_);
    row.has_error = true;
    row.rmse = e.rmse;
    row.relmse = e.relmse;
  }
  rows_.push_back(row);
}

void write_convergence_log(const std::string& path, const std::vector<LogRow>& rows) {
  write_atomically(path, [&](const std::string& tmp) {
    write_stream_file(tmp, path, [&](std::ostream& out) {
      out << "integrator,pass,seconds,camera_paths,photons,rmse,relmse\n" << std::setprecision(9);
      for (const LogRow& r : rows) {
        out << r.integrator << "," << r.pass << "," << r.seconds << "," << r.camera_paths << ","
            << r.photons << ",";
        if (r.has_error)
          out << r.rmse << "," << r.relmse;
        else
          out << ",";
        out << "\n";
      }
    });
  });
}

std::vector<LogRow> read_convergence_log(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open file");
  std::string line;
  std::getline(in, line);
  std::vector<LogRow> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (line.back() == ',') cells.push_back("");
    if (cells.size() != 7) throw Error(path + ": malformed log row: " + line);
    LogRow r;
    r.integrator = cells[0];
    r.pass = std::stoi(cells[1]);
    r.seconds = std::stod(cells[2]);
    r.camera_paths = std::stoll(cells[3]);
    r.photons = std::stoll(cells[4]);
    r.has_error = !cells[5].empty();
    if (r.has_error) r.rmse = std::stod(cells[5]), r.relmse = std::stod(cells[6]);
    rows.push_back(r);
  }
  return rows;
}

double loglog_slope(const std::vector<LogRow>& rows, bool relmse, double from_seconds) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const LogRow& r : rows) {
    double e = relmse ? r.relmse : r.rmse;
    if (!r.has_error || r.seconds < from_seconds || !(e > 0) || !(r.seconds > 0)) continue;
    double x = std::log(r.seconds), y = std::log(e);
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
  }
  if (n < 3) return NAN;
  double den = n * sxx - sx * sx;
  return den > 0 ? (n * sxy - sx * sy) / den : NAN;
}

double startup_seconds(const std::vector<LogRow>& rows) {
  if (rows.size() < 3) return 0;
  std::vector<double> durations;
  for (size_t i = 1; i < rows.size(); ++i)
    durations.push_back(rows[i].seconds - rows[i - 1].seconds);
  std::nth_element(durations.begin(), durations.begin() + durations.size() / 2, durations.end());
  return std::max(0.0, rows[0].seconds - durations[durations.size() / 2]);
}

std::vector<LogRow> without_startup(const std::vector<LogRow>& rows) {
  double s = startup_seconds(rows);
  std::vector<LogRow> out = rows;
  for (LogRow& r : out) r.seconds -= s;
  return out;
}

double time_to_reach(const std::vector<LogRow>& rows, double target) {
  for (const LogRow& r : rows)
    if (r.has_error && r.rmse <= target) return r.seconds;
  return -1;
}

}  // namespace kasha
