#include "material/coat.h"

#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>
#include <vector>

#include "material/ggx.h"

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
template <typename G>
static double cosine_mean(G g) {
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

namespace {

using Ggx = HostGgx;

// The reflection lobe's albedo and the transmittance (flux: no 1/η²) of a rough interface of
// relative index eta for light from the side at cos θ = mu: the mean of F·G/G1 over reflected
// and of (1 − F)·G/G1 over refracted visible-normal samples on a stratified grid.
void lobe_albedos(const Ggx& a, double eta, double mu, double& reflect, double& transmit) {
  const int n = 128;
  const Eigen::Vector3d wo(std::sqrt(std::max(0.0, 1 - mu * mu)), 0, mu);
  double r = 0, t = 0;
  const double g1 = a.g1(wo);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector3d m = a.sample_visible(wo, (i + 0.5) / n, (j + 0.5) / n);
      const double c = wo.dot(m), F = fresnel_dielectric(c, eta);
      const Eigen::Vector3d wr = -wo + 2 * c * m;
      if (wr.z() > 0) r += F * a.g(wo, wr) / g1;
      const double s2 = (1 - c * c) / (eta * eta);
      if (s2 < 1) {
        const Eigen::Vector3d wt = (-wo / eta + (c / eta - std::sqrt(1 - s2)) * m).normalized();
        if (wt.z() < 0) t += (1 - F) * a.g(wo, wt) / g1;
      }
    }
  reflect = r / (n * n);
  transmit = t / (n * n);
}

CoatTables compute_rough_coat_tables(const CoatDesc& coat) {
  const Ggx a{coat.alpha};
  const int K = kCoatTableSize;
  CoatTables out;
  out.reflect.resize(K);
  out.transmit.resize(K);
  std::vector<double> inside(K);
  // Each μ node on its own: 2 · 128² visible-normal samples, the bulk of a rough coat's cost.
  tbb::parallel_for(0, K, [&](int k) {
    const double mu = std::max(1e-3, static_cast<double>(k) / (K - 1));
    double r, t, ri, ti;
    lobe_albedos(a, coat.eta, mu, r, t);
    lobe_albedos(a, 1 / coat.eta, mu, ri, ti);
    const double s2 = (1 - mu * mu) / (coat.eta * coat.eta);
    const double mu_t = s2 < 1 ? std::sqrt(1 - s2) : 0.0;
    out.reflect[k] = r;
    out.transmit[k] = mu_t > 0 ? t * layer(coat.thickness, mu_t) : 0.0;
    inside[k] = ri;
  });
  // Linear in μ between the nodes, integrated with the layer's exp(−2d/μ) on a fine grid.
  out.internal = cosine_mean(
      [&](double mu) { return coat_table_at(inside, mu) * layer(2 * coat.thickness, mu); });
  out.mean = coat_table_mean(out.transmit);
  return out;
}

}  // namespace

double coat_table_at(const std::vector<double>& table, double mu) {
  const double x = std::clamp(mu, 0.0, 1.0) * (kCoatTableSize - 1);
  const int k = std::min(kCoatTableSize - 2, static_cast<int>(x));
  return table[k] + (x - k) * (table[k + 1] - table[k]);
}

double coat_table_mean(const std::vector<double>& table) {
  return cosine_mean([&](double mu) { return coat_table_at(table, mu); });
}

// Scenes give many materials one coat (Bitterli's kitchen: dozens of rough coateddiffuse
// materials with a few roughnesses): each distinct coat's tables are computed once.
CoatTables rough_coat_tables(const CoatDesc& coat) {
  static std::mutex mutex;
  static std::map<std::tuple<double, double, double>, CoatTables> cache;
  const auto key = std::make_tuple(coat.eta, coat.thickness, coat.alpha);
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
  }
  CoatTables t = compute_rough_coat_tables(coat);
  std::lock_guard<std::mutex> lock(mutex);
  return cache.emplace(key, std::move(t)).first->second;
}

}  // namespace kasha
