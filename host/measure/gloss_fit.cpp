#include "measure/gloss_fit.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/csv_table.h"
#include "core/error.h"
#include "core/printable.h"

namespace kasha {

GlossFit fit_gloss(const std::string& path, double cone_deg) {
  CsvTable t = read_csv_table(path);
  // Spectra Manager exports spectra over wavelength or wavenumber, never angles.
  if (t.jasco)
    throw Error(printable(path) +
                ": a JASCO spectrum export is not a gloss table (columns "
                "theta_in_deg, theta_out_deg, brdf)");
  if (t.rows.empty()) throw Error(printable(path) + ": no goniometer rows");
  // theta_in -> (theta_out, brdf) samples.
  std::map<double, std::vector<std::pair<double, double>>> by_incidence;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    if (row.size() != 3)
      throw Error(path + ": line " + std::to_string(t.row_lines[r]) +
                  ": expected theta_in_deg, theta_out_deg, brdf");
    if (row[2] < 0)
      throw Error(path + ": line " + std::to_string(t.row_lines[r]) + ": negative BRDF");
    if (std::abs(row[0]) >= 90 || std::abs(row[1]) >= 90)
      throw Error(path + ": line " + std::to_string(t.row_lines[r]) +
                  ": angles must lie within (-90, 90) degrees");
    by_incidence[row[0]].push_back({row[1], row[2]});
  }

  GlossFit fit;
  std::map<double, std::pair<double, int>> lobe;  // |δ| in degrees -> (sum of g·p, count)
  double floor_sum = 0;
  for (auto& [theta_in, samples] : by_incidence) {
    std::vector<double> outside;
    for (auto [theta_out, brdf] : samples)
      if (std::abs(theta_out - theta_in) > cone_deg) outside.push_back(brdf);
    if (outside.empty())
      throw Error(path + ": incidence " + std::to_string(theta_in) +
                  " deg has no samples outside the " + std::to_string(cone_deg) +
                  " deg cone to measure the diffuse floor");
    std::nth_element(outside.begin(), outside.begin() + outside.size() / 2, outside.end());
    double floor = outside[outside.size() / 2];
    floor_sum += floor;
    for (auto [theta_out, brdf] : samples) {
      double delta = std::abs(theta_out - theta_in);
      if (delta > cone_deg) continue;
      double gp = std::max(0.0, brdf - floor) * std::cos(theta_out * M_PI / 180.0);
      auto& [sum, count] = lobe[std::round(delta * 1e6) / 1e6];
      sum += gp;
      ++count;
    }
  }
  fit.incidence_angles = static_cast<int>(by_incidence.size());
  fit.diffuse_floor = floor_sum / fit.incidence_angles;
  if (lobe.empty())
    throw Error(path + ": no samples within the " + std::to_string(cone_deg) + " deg cone");

  std::vector<double> deg, gp;
  for (auto& [d, s] : lobe) deg.push_back(d), gp.push_back(s.first / s.second);
  if (deg.front() > 0) deg.insert(deg.begin(), 0.0), gp.insert(gp.begin(), gp.front());
  // g = 2π ∫ g·p(δ) sin δ dδ, trapezoid over the samples (the lobe is zero past the last one).
  double g = 0;
  for (size_t k = 0; k + 1 < deg.size(); ++k) {
    double d0 = deg[k] * M_PI / 180, d1 = deg[k + 1] * M_PI / 180;
    g += 0.5 * (d1 - d0) * (gp[k] * std::sin(d0) + gp[k + 1] * std::sin(d1));
  }
  g *= 2 * M_PI;
  fit.gloss.reflectance = g;
  fit.gloss.cone_deg = cone_deg;
  fit.gloss.profile_deg = deg;
  for (double v : gp) fit.gloss.profile_value.push_back(g > 0 ? v / g : 0.0);
  return fit;
}

}  // namespace kasha
