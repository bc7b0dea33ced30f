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

// The light a walk carries out of the layer (or, for the coat's reflection, off it): a scalar
// weight and the metal bounces it took, whose Fresnel factors each bin applies.
struct Exit {
  double weight = 0;
  std::vector<double> cos_m;
  bool coat = false;  // reflected by the coat without entering
};

using Vec = Eigen::Vector3d;

// Light meeting an interface of relative index eta (the far side's over the near side's) from
// the side z > 0, going along -w: a visible facet (a smooth interface's is the normal), then
// reflection with the facet's Fresnel reflectance or refraction, as pbrt-v4's DielectricBxDF
// samples; *d the direction of travel after it, the weight G/G1 (flux). False: lost.
bool cross_interface(const HostGgx& ggx, bool smooth, double eta, const Vec& w, double u0,
                     double u1, double uc, Vec* d, double* weight, bool* reflected) {
  const Vec m = smooth ? Vec(0, 0, 1) : ggx.sample_visible(w, u0, u1);
  const double c = w.dot(m), F = fresnel_dielectric(c, eta);
  *reflected = uc < F;
  if (*reflected) {
    *d = -w + 2 * c * m;
    if (d->z() <= 0) return false;
  } else {
    const double s2 = (1 - c * c) / (eta * eta);
    *d = (-w / eta + (c / eta - std::sqrt(std::max(0.0, 1 - s2))) * m).normalized();
    if (d->z() >= 0) return false;
  }
  const Vec back = *reflected ? *d : Vec(-*d);
  *weight = smooth ? 1.0 : ggx.g(w, Vec(back.x(), back.y(), std::abs(back.z()))) / ggx.g1(w);
  return true;
}

// pbrt-v4's layered walk (LayeredBxDF) as flux: light arriving at cos θ = mu meets the coat,
// enters, and bounces between the metal and the coat's underside until it leaves or is lost;
// every bounce kept (pbrt-v4 stops at maxdepth, five metal bounces by default).
Exit walk(const CoatDesc& coat, const HostGgx& top, const HostGgx& metal, double mu,
          std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const bool smooth = !coat.rough();
  Exit out;
  Vec d, w(std::sqrt(std::max(0.0, 1 - mu * mu)), 0, mu);
  double g;
  bool reflected;
  if (!cross_interface(top, smooth, coat.eta, w, u(rng), u(rng), u(rng), &d, &g, &reflected))
    return out;
  out.weight = g;
  if (reflected) {
    out.coat = true;
    return out;
  }
  for (int bounce = 0; bounce < 64; ++bounce) {
    w = -d;  // pointing up, away from the metal
    out.weight *= std::exp(-coat.thickness / w.z());
    const Vec m = metal.sample_visible(w, u(rng), u(rng));
    const Vec r = -w + 2 * w.dot(m) * m;
    if (r.z() <= 0) break;
    out.cos_m.push_back(w.dot(m));
    out.weight *= metal.g(w, r) / metal.g1(w) * std::exp(-coat.thickness / r.z());
    // The coat from below: in a frame turned over, it is met from z > 0.
    const Vec flipped(-r.x(), -r.y(), r.z());
    if (!cross_interface(top, smooth, 1 / coat.eta, flipped, u(rng), u(rng), u(rng), &d, &g,
                         &reflected))
      break;
    out.weight *= g;
    if (!reflected) return out;       // left through the coat
    d = Vec(-d.x(), -d.y(), -d.z());  // back down, in the layer's frame
  }
  out.weight = 0;
  return out;
}

// The albedo of the kernels' once-scattered metal lobe (metal_under_coat.h) at cos θ = mu for
// one visible normal: t(μo) G/G1 t(μi), and the facet's cosine for Fc; 0 where it leaves below
// the horizon or beyond the coat's escape cone.
double once_scattered(const CoatView& c, const HostGgx& ggx, double mu, double u0, double u1,
                      double* cos_m) {
  const double eta = c.coat.eta, s = std::sqrt(std::max(0.0, 1 - mu * mu)) / eta;
  const Vec v(s, 0, std::sqrt(std::max(0.0, 1 - s * s)));
  const Vec m = ggx.sample_visible(v, u0, u1);
  *cos_m = v.dot(m);
  const Vec r = -v + 2 * *cos_m * m;
  const double sin2_out = (1 - r.z() * r.z()) * eta * eta;
  if (r.z() <= 0 || sin2_out >= 1) return 0;
  return c.transmission(mu) * ggx.g(v, r) / ggx.g1(v) * c.transmission(std::sqrt(1 - sin2_out));
}

}  // namespace

LayeredMetalParts layered_metal_parts(const CoatDesc& coat, double alpha_metal, double alpha,
                                      const std::vector<double>& eta,
                                      const std::vector<double>& k) {
  const CoatView c{coat, coat.rough() ? rough_coat_tables(coat) : CoatTables{}};
  const HostGgx top{coat.alpha}, metal{std::max(alpha_metal, 1e-4)}, lobe{alpha};
  const int paths = 1 << 15, bins = static_cast<int>(eta.size());
  std::mt19937_64 rng(0x6b617368);
  std::uniform_real_distribution<double> u(0, 1);
  // Per bin: the walk's light that leaves the layer, and what the kernels' once-scattered lobe
  // gives; the coated Lambert part carries the difference.
  std::vector<double> layer(bins, 0), once(bins, 0), first(bins, 0);
  double reflect = 0;
  for (int p = 0; p < paths; ++p) {
    const double mu = std::sqrt((p + u(rng)) / paths);  // cosine-weighted incidence, stratified
    reflect += c.reflection(mu);
    const Exit e = walk(coat, top, metal, mu, rng);
    double cos_m;
    const double o = once_scattered(c, lobe, mu, u(rng), u(rng), &cos_m);
    for (int i = 0; i < bins; ++i) {
      const double n = eta[i] / coat.eta, kk = k[i] / coat.eta;
      if (o > 0) once[i] += o * fresnel_complex(cos_m, n, kk);
      if (e.coat || e.weight == 0) continue;
      double w = e.weight;
      for (double cm : e.cos_m) w *= fresnel_complex(cm, n, kk);
      layer[i] += w;
      if (e.cos_m.size() == 1) first[i] += w;
    }
  }
  // The once-scattered lobe crosses the coat by smooth refraction; through a rough coat the walk's
  // light that meets the metal once leaves less (facets that turn it back, masking at both
  // crossings): the lobe is scaled to the walk's share, the same at every wavelength (it varies by
  // under 0.5 % between bins for gold).
  double first_sum = 0, once_sum = 0;
  for (int i = 0; i < bins; ++i) {
    first_sum += first[i];
    once_sum += once[i];
  }
  LayeredMetalParts parts;
  parts.once_scale = once_sum > 0 ? first_sum / once_sum : 1.0;
  // A coated Lambert part of ρ' = ρ / (1 − R̄ρ) has albedo τ̄² ρ' / η² under uniform light.
  const double tau = coat.rough() ? c.tables.mean : coat_mean_transmission(coat);
  const double internal = coat.rough() ? c.tables.internal : coat_internal_reflectance(coat);
  double once_mean = 0, rest_mean = 0;
  for (int i = 0; i < bins; ++i) {
    const double rest = std::max(0.0, layer[i] - parts.once_scale * once[i]) / paths;
    once_mean += parts.once_scale * once[i] / paths / bins;
    rest_mean += rest / bins;
    const double rho_eff = rest * coat.eta * coat.eta / (tau * tau);
    parts.scattered.push_back(rho_eff / (1 + internal * rho_eff));
  }
  // Each part is chosen at points in proportion to its albedo (within [0.1, 0.9]), so neither
  // scale is large.
  const double lambert = reflect / paths + rest_mean;
  parts.lambert_share = std::clamp(lambert / std::max(1e-9, lambert + once_mean), 0.1, 0.9);
  return parts;
}

}  // namespace kasha
