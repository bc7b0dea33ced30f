#include "measure/measurement_plots.h"

#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/python_script.h"

namespace kasha {

static void write_matrix(const std::filesystem::path& file, const std::string& who,
                         const MeasuredMaterial& m, const Eigen::MatrixXd& v) {
  write_stream_file(file.string(), who + ": " + file.filename().string(), [&](std::ostream& out) {
    out << "lambda_out_nm\\lambda_in_nm";
    for (double l : m.ex_nm) out << "," << l;
    out << "\n";
    for (Eigen::Index o = 0; o < v.rows(); ++o) {
      out << m.em_nm[o];
      for (Eigen::Index i = 0; i < v.cols(); ++i) out << "," << v(o, i);
      out << "\n";
    }
  });
}

static void write_spectrum(const std::filesystem::path& file, const std::string& who,
                           const Tabulated& t) {
  write_stream_file(file.string(), who + ": " + file.filename().string(), [&](std::ostream& out) {
    out << "nm,value\n";
    for (size_t k = 0; k < t.nm.size(); ++k) out << t.nm[k] << "," << t.value[k] << "\n";
  });
}

void write_measurement_plots(const std::string& dir, const MeasuredMaterial& m,
                             const std::string& who) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(who + ": cannot create directory: " + ec.message());
  fs::path d(dir);
  write_matrix(d / "raw_matrix.csv", who, m, m.raw);
  // Unknown entries (band, second order) as NaN so the plot leaves them blank.
  Eigen::MatrixXd offband = m.fluorescence;
  for (Eigen::Index o = 0; o < offband.rows(); ++o)
    for (Eigen::Index i = 0; i < offband.cols(); ++i)
      if (m.known(o, i) == 0) offband(o, i) = NAN;
  write_matrix(d / "offband_matrix.csv", who, m, offband);
  Eigen::MatrixXd residual = offband - m.fit;
  write_matrix(d / "fit_residual.csv", who, m, residual);
  write_spectrum(d / "passive.csv", who, m.passive);
  write_spectrum(d / "excitation.csv", who, m.excitation);
  write_spectrum(d / "emission.csv", who, m.emission);

  run_embedded_python("plot_measurement.py", {d.string(), std::to_string(m.rank1_residual)}, who);
}

}  // namespace kasha
