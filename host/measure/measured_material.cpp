#include "measure/measured_material.h"

#include <algorithm>
#include <sstream>

#include "core/error.h"
#include "core/printable.h"

namespace kasha {

MeasuredMaterial measured_from(const ExcitationEmissionMatrix& d, const std::string& method) {
  MeasuredMaterial m;
  m.source = d.source;
  m.method = method;
  m.ex_nm = d.ex_nm;
  m.em_nm = d.em_nm;
  m.raw = d.value;
  return m;
}

double interpolate(const Tabulated& t, double nm) {
  if (t.nm.empty() || nm < t.nm.front() || nm > t.nm.back()) return 0.0;
  size_t k = std::upper_bound(t.nm.begin(), t.nm.end(), nm) - t.nm.begin();
  if (k == 0) return t.value.front();
  if (k >= t.nm.size()) return t.value.back();
  double u = (nm - t.nm[k - 1]) / (t.nm[k] - t.nm[k - 1]);
  return t.value[k - 1] + u * (t.value[k] - t.value[k - 1]);
}

void drop_zero_fluorescence(MeasuredMaterial& m) {
  auto zero = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return x == 0; });
  };
  if (m.excitation.nm.empty() || !(zero(m.excitation.value) || zero(m.emission.value))) return;
  m.excitation = {};
  m.emission = {};
  m.notes.push_back(
      "no fluorescence: the readings off the band fit to zero, so the material is "
      "passive only");
}

void check_energy(MeasuredMaterial& m, bool clip) {
  const double g = m.gloss ? m.gloss->reflectance : 0.0;
  m.max_energy = 0;
  // Every wavelength where either part is tabulated.
  std::vector<double> nm = m.excitation.nm;
  nm.insert(nm.end(), m.passive.nm.begin(), m.passive.nm.end());
  std::sort(nm.begin(), nm.end());
  nm.erase(std::unique(nm.begin(), nm.end()), nm.end());
  for (double l : nm) {
    double rho = interpolate(m.passive, l), a = interpolate(m.excitation, l), total = g + rho + a;
    if (total > m.max_energy) m.max_energy = total, m.max_energy_nm = l;
    if (total <= 1.0 + 1e-9) continue;
    if (!clip) {
      std::ostringstream msg;
      if (!m.source.empty()) msg << printable(m.source) << ": ";
      msg << "energy gain at " << l << " nm: gloss " << g << " + passive " << rho
          << " + excitation " << a << " = " << total << " > 1 (use --clip to clip it)";
      throw Error(msg.str());
    }
    m.clipped_nm.push_back(l);
    double excess = total - 1.0;
    for (size_t i = 0; i < m.passive.nm.size(); ++i)
      if (m.passive.nm[i] == l) {
        double cut = std::min(excess, m.passive.value[i]);
        m.passive.value[i] -= cut;
        excess -= cut;
      }
    for (size_t i = 0; i < m.excitation.nm.size() && excess > 0; ++i)
      if (m.excitation.nm[i] == l)
        m.excitation.value[i] = std::max(0.0, m.excitation.value[i] - excess);
  }
}

}  // namespace kasha
