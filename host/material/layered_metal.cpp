#include "material/layered_metal.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>

#include "material/ggx.h"

namespace kasha {

double layered_metal_alpha(const CoatDesc& coat, double alpha_metal) {
  const double spread = coat.rough() ? coat.alpha * (1 - 1 / coat.eta) : 0.0;
  return std::max(1e-3, std::sqrt(alpha_metal * alpha_metal + spread * spread / 2));
}

namespace {

// pbrt-v4's FrComplex: a conductor's Fresnel reflectance at cos θ, index eta + ik.
double fresnel_complex(double cos_i, double eta, double k) {
  using C = std::complex<double>;
  const C n(eta, k);
  const double c = std::clamp(cos_i, 0.0, 1.0), s2 = 1 - c * c;
  const C cos_t = std::sqrt(C(1) - C(s2) / (n * n));
  const C r_parl = (n * c - cos_t) / (n * c + cos_t), r_perp = (c - n * cos_t) / (c + n * cos_t);
  return (std::norm(r_parl) + std::norm(r_perp)) / 2;
}

// The coat as the walk sees it: t(μ) for light crossing it at cos θ = μ outside (either way),
// and the albedo of its reflection from outside.
struct CoatView {
  const CoatDesc& coat;
  CoatTables tables;
  double at(const std::vector<double>& v, double mu) const {
    const double x = std::clamp(mu, 0.0, 1.0) * (kCoatTableSize - 1);
    const int i = std::min(kCoatTableSize - 2, static_cast<int>(x));
    return v[i] + (x - i) * (v[i + 1] - v[i]);
  }
  double transmission(double mu) const {
    return coat.rough() ? at(tables.transmit, mu) : coat_transmission(coat, mu);
  }
  double reflection(double mu) const {
    return coat.rough() ? at(tables.reflect, mu) : fresnel_dielectric(mu, coat.eta);
  }
};

// One bounce of a walk under the coat: the metal's G/G1 and facet cosine, and of the light it
// sends up, the share that leaves (t at the outside's cosine) and the share the coat returns.
struct Bounce {
  double g, cos_m, leave, back;
};

// A walk from light arriving at cos θ = mu outside, until the metal sends it below the horizon
// or 32 bounces (at 0.95 per bounce and more than half returned, under 1e-3 is left by then).
std::vector<Bounce> walk(const CoatView& c, const HostGgx& ggx, double mu, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const double eta = c.coat.eta, s = std::sqrt(std::max(0.0, 1 - mu * mu)) / eta;
  Eigen::Vector3d v(s, 0, std::sqrt(std::max(0.0, 1 - s * s)));  // pointing up, inside
  std::vector<Bounce> out;
  for (int b = 0; b < 32; ++b) {
    const Eigen::Vector3d m = ggx.sample_visible(v, u(rng), u(rng));
    const double cos_m = v.dot(m);
    const Eigen::Vector3d r = -v + 2 * cos_m * m;
    if (r.z() <= 0) break;
    const double sin2_out = (1 - r.z() * r.z()) * eta * eta;
    const double mu_out = sin2_out < 1 ? std::sqrt(1 - sin2_out) : 0.0;
    const double layer2 = std::exp(-2 * c.coat.thickness / r.z());
    const double back = (mu_out > 0 ? fresnel_dielectric(r.z(), 1 / eta) : 1.0) * layer2;
    out.push_back(
        {ggx.g(v, r) / ggx.g1(v), cos_m, mu_out > 0 ? c.transmission(mu_out) : 0.0, back});
    v = Eigen::Vector3d(-r.x(), -r.y(), r.z());
  }
  return out;
}

}  // namespace

LayeredMetalParts layered_metal_parts(const CoatDesc& coat, double alpha,
                                      const std::vector<double>& eta,
                                      const std::vector<double>& k) {
  const CoatView c{coat, coat.rough() ? rough_coat_tables(coat) : CoatTables{}};
  const HostGgx ggx{alpha};
  const int paths = 4096, bins = static_cast<int>(eta.size());
  std::mt19937_64 rng(0x6b617368);
  std::vector<double> single(bins, 0), multiple(bins, 0);
  double reflect = 0;
  for (int p = 0; p < paths; ++p) {
    const double mu = std::sqrt((p + 0.5) / paths);  // cosine-weighted incidence, stratified
    reflect += c.reflection(mu);
    const std::vector<Bounce> w = walk(c, ggx, mu, rng);
    for (int i = 0; i < bins; ++i) {
      double beta = c.transmission(mu);
      for (size_t b = 0; b < w.size() && beta > 1e-6; ++b) {
        beta *= w[b].g * fresnel_complex(w[b].cos_m, eta[i] / coat.eta, k[i] / coat.eta);
        (b == 0 ? single[i] : multiple[i]) += beta * w[b].leave;
        beta *= w[b].back;
      }
    }
  }
  // A coated Lambert part of ρ' = ρ / (1 − R̄ρ) has albedo τ̄² ρ' / η² under uniform light.
  const double tau = coat.rough() ? c.tables.mean : coat_mean_transmission(coat);
  const double internal = coat.rough() ? c.tables.internal : coat_internal_reflectance(coat);
  LayeredMetalParts parts;
  double single_mean = 0, multiple_mean = 0;
  for (int i = 0; i < bins; ++i) {
    single_mean += single[i] / paths / bins;
    multiple_mean += multiple[i] / paths / bins;
    const double rho_eff = multiple[i] / paths * coat.eta * coat.eta / (tau * tau);
    parts.scattered.push_back(rho_eff / (1 + internal * rho_eff));
  }
  // Each part is chosen at points in proportion to its albedo (within [0.1, 0.9]), so neither
  // scale is large.
  const double lambert = reflect / paths + multiple_mean;
  parts.lambert_share = std::clamp(lambert / std::max(1e-9, lambert + single_mean), 0.1, 0.9);
  return parts;
}

}  // namespace kasha
