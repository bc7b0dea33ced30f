#pragma once
// The convergence log of docs/formats.md#convergence-log: a row after every pass.
//   integrator,pass,seconds,camera_paths,photons,rmse,relmse
#include <optional>
#include <string>
#include <vector>

#include "film/image.h"
#include "render/pass_observer.h"

namespace kasha {

struct LogRow {
  std::string integrator;
  int pass = 0;
  double seconds = 0;  // render time so far, not counting the error evaluation itself
  long long camera_paths = 0, photons = 0;
  bool has_error = false;
  double rmse = 0, relmse = 0;
};

// The log as a render's observer: a row after every pass, with the error against `reference`
// when there is one (evaluated outside the render's time).
class ConvergenceLog : public PassObserver {
 public:
  explicit ConvergenceLog(std::optional<Image> reference = std::nullopt)
      : reference_(std::move(reference)) {}
  void pass_done(const PassRecord& record, const Film& film) override;
  const std::vector<LogRow>& rows() const { return rows_; }

 private:
  std::optional<Image> reference_;
  std::vector<LogRow> rows_;
};

void write_convergence_log(const std::string& path, const std::vector<LogRow>& rows);
std::vector<LogRow> read_convergence_log(const std::string& path);

// Least-squares slope of log(error) over log(seconds), using the rows after `from_seconds`
// with a positive error; NaN when fewer than three rows qualify.
double loglog_slope(const std::vector<LogRow>& rows, bool relmse, double from_seconds);
// The one-time start-up inside the first pass (a device compiling kernels at their first launch):
// how much longer the first pass took than the median pass.
double startup_seconds(const std::vector<LogRow>& rows);
// The rows with the start-up taken off their times (for fitting rates of convergence).
std::vector<LogRow> without_startup(const std::vector<LogRow>& rows);

// The first time the RMSE is at or below `target`, or a negative value if never.
double time_to_reach(const std::vector<LogRow>& rows, double target);

}  // namespace kasha
