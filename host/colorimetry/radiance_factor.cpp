#include "colorimetry/radiance_factor.h"

#include <algorithm>
#include <cmath>

namespace kasha {

std::vector<double> RadianceFactor::total() const {
  std::vector<double> out(reflected.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = reflected[i] + fluorescent[i];
  return out;
}

// Σ_i a_i S_i: the lamp's radiance absorbed and re-emitted, before the emission shape spreads it.
static double excited(const Material& m, const std::vector<double>& lamp) {
  double sum = 0;
  for (size_t i = 0; i < m.a.size(); ++i) sum += m.a[i] * lamp[i];
  return sum;
}

std::vector<double> leaving_radiance(const Material& m, const std::vector<double>& lamp) {
  std::vector<double> out(lamp.size(), 0.0);
  const double fluorescence = m.fluorescent() ? excited(m, lamp) : 0.0;
  for (size_t j = 0; j < lamp.size(); ++j) {
    if (!m.rho.empty()) out[j] += m.rho[j] * lamp[j];
    if (m.fluorescent()) out[j] += m.e_hat[j] * fluorescence;
  }
  return out;
}

RadianceFactor radiance_factor(const Material& m, const std::vector<double>& lamp) {
  RadianceFactor r;
  r.reflected = m.rho.empty() ? std::vector<double>(lamp.size(), 0.0) : m.rho;
  r.fluorescent.assign(lamp.size(), 0.0);
  const double peak = *std::max_element(lamp.begin(), lamp.end());
  const double fluorescence = m.fluorescent() ? excited(m, lamp) : 0.0;
  for (size_t j = 0; j < lamp.size(); ++j) {
    const double emitted = m.fluorescent() ? m.e_hat[j] * fluorescence : 0.0;
    if (emitted == 0)
      r.fluorescent[j] = 0;
    else
      r.fluorescent[j] = lamp[j] > kUnlitFraction * peak ? emitted / lamp[j] : std::nan("");
  }
  return r;
}

}  // namespace kasha
