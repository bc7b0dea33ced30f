#include "material/coat.h"

#include <algorithm>
#include <cmath>

namespace kasha {

double fresnel_dielectric(double cos_i, double eta) {
  cos_i = std::clamp(cos_i, 0.0, 1.0);
  const double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1) return 1;
  const double cos_t = std::sqrt(1 - sin2_t);
  const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5 * (rp * rp + rs * rs);
}

// The layer's transmittance along a direction at cos θ to the normal.
static double layer(double thickness, double cos_theta) {
  return thickness > 0 ? std::exp(-thickness / cos_theta) : 1.0;
}

double coat_transmission(const CoatDesc& coat, double cos_theta) {
  cos_theta = std::clamp(cos_theta, 0.0, 1.0);
  const double sin2_t = (1 - cos_theta * cos_theta) / (coat.eta * coat.eta);
  if (sin2_t >= 1) return 0;
  const double cos_t = std::sqrt(1 - sin2_t);
  return (1 - fresnel_dielectric(cos_theta, coat.eta)) * layer(coat.thickness, cos_t);
}

// ∫₀¹ g(μ) 2μ dμ (cos θ dω / π over a hemisphere) by Gauss–Legendre on panels that crowd towards
// μ = 0, where exp(−d/μ) and the critical angle of total internal reflection bend g sharply.
template <typename G> static double cosine_mean(G g) {
  static const double x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                              -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                              0.7966664774136267,  0.9602898564975363};
  static const double w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                              0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                              0.2223810344533745, 0.1012285362903763};
  const int panels = 4096;
  double sum = 0;
  for (int p = 0; p < panels; ++p) {
    const double a0 = static_cast<double>(p) / panels, a1 = static_cast<double>(p + 1) / panels;
    const double lo = a0 * a0, hi = a1 * a1;
    for (int k = 0; k < 8; ++k) {
      const double mu = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x[k];
      sum += 0.5 * (hi - lo) * w[k] * g(mu) * 2 * mu;
    }
  }
  return sum;
}

double coat_internal_reflectance(const CoatDesc& coat) {
  return cosine_mean([&](double mu) {
    return fresnel_dielectric(mu, 1 / coat.eta) * layer(2 * coat.thickness, mu);
  });
}

double coat_mean_transmission(const CoatDesc& coat) {
  return cosine_mean([&](double mu) { return coat_transmission(coat, mu); });
}

}  // namespace kasha
